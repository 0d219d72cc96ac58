"""What a benchmark ran on: wall times are only comparable on the same CPU and BLAS kernels
(docs/speed.md, Machines); and the BLAS environment every benchmark starts needlefem with."""
import os
import platform
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def use_blas_environment(exe):
    """Exports, for every needlefem this process starts, the OpenBLAS kernels this CPU should run
    where OpenBLAS does not know its model (scripts/blas_env.sh, which asks `exe`)."""
    exports = subprocess.run([str(ROOT / "scripts" / "blas_env.sh"), str(exe)], capture_output=True, text=True,
                             check=True).stdout
    for line in exports.splitlines():
        name, value = line.removeprefix("export ").split("=", 1)
        os.environ[name] = value


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
