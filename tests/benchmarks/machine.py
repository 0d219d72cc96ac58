"""What a benchmark ran on: wall times are only comparable on the same CPU and BLAS kernels (the
same build ran the tied brain-tip benchmark in 12.8 s on one 2-core machine and 16.8 s on another,
24.9 s there before needlefem chose OpenBLAS's kernels itself: integration/blas_threads.hpp)."""
import os
import platform


def describe_machine():
    """CPU model and count of this machine, for a benchmark's JSON (the BLAS kernels each run used
    are in its summary's solver.blas_kernel)."""
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {"cpu_model": model, "cpu_count": os.cpu_count()}
