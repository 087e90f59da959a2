# Sourced by scripts/test, scripts/verify and scripts/bench: pins the kernels OpenBLAS
# runs, so that a run gives the same numbers, to the last bit, on any x86-64 processor
# with AVX2 and FMA. Left to itself OpenBLAS picks kernels for the processor it finds
# (Cooperlake on an AVX-512 EPYC, Zen or Haswell on others), and long runs with many
# contact-state decisions end differently between them (docs/design_notes.md section 32).
# Haswell's kernels need AVX2 and FMA only, and cost no measurable time here (the
# Marcellus quick case: 9.7 s under Haswell, Zen and Cooperlake).
#
# An OPENBLAS_CORETYPE already set is kept (say OPENBLAS_CORETYPE= to let OpenBLAS
# choose). A processor without AVX2 and FMA keeps OpenBLAS's own choice, and says so.
if [[ -z "${OPENBLAS_CORETYPE+set}" ]]; then
  if [[ "$(uname -m)" == x86_64 ]] && grep -qw avx2 /proc/cpuinfo 2>/dev/null &&
     grep -qw fma /proc/cpuinfo 2>/dev/null; then
    export OPENBLAS_CORETYPE=Haswell
  else
    echo "blas_kernels: no AVX2 and FMA on this processor; OpenBLAS chooses its kernels," \
         "so long runs may differ in the last bits from the report (docs/design_notes.md section 32)" >&2
  fi
fi
