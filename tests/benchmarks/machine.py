"""What a benchmark ran on: wall times are only comparable on the same CPU and BLAS kernels
(integration/blas_threads.hpp; the same build on two machines: docs/speed.md)."""
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
