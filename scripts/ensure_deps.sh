#!/usr/bin/env bash
# Installs the Debian packages shellbench needs, only when something is
# missing, and says what it installs.  Safe to run repeatedly.
set -euo pipefail
need=()
have_hdr() { [ -e "$1" ]; }
have_hdr /usr/include/suitesparse/cholmod.h       || need+=(libsuitesparse-dev)
have_hdr /usr/lib/x86_64-linux-gnu/libopenblas.so || ls /usr/lib/*/libopenblas.so >/dev/null 2>&1 || need+=(libopenblas-dev)
have_hdr /usr/include/hdf5/serial/hdf5.h          || need+=(libhdf5-dev)
command -v h5dump >/dev/null 2>&1                 || need+=(hdf5-tools)
have_hdr /usr/include/gsl/gsl_math.h              || need+=(libgsl-dev)
have_hdr /usr/include/jansson.h                   || need+=(libjansson-dev)
have_hdr /usr/include/zlib.h                      || need+=(zlib1g-dev)      # PNG output of shellbench render
have_hdr /usr/include/opensubdiv/version.h        || need+=(libosd-dev)
command -v gnuplot >/dev/null 2>&1                || need+=(gnuplot-nox)
command -v pkg-config >/dev/null 2>&1             || need+=(pkg-config)
command -v cc >/dev/null 2>&1                     || need+=(gcc)
command -v c++ >/dev/null 2>&1                    || need+=(g++)
command -v make >/dev/null 2>&1                   || need+=(make)
command -v git >/dev/null 2>&1                    || need+=(git)
command -v python3 >/dev/null 2>&1                || need+=(python3)    # benchmark report scripts (standard library only)
# shellbench site (docs/site.md): Vega 5 draws the plots in the pages (copied into every site);
# make check-site and the short browser check in make test: headless Chromium driven by node
[ -e /usr/share/javascript/vega/vega-view.min.js ] || need+=(libjs-vega)
command -v chromium >/dev/null 2>&1               || need+=(chromium)
command -v node >/dev/null 2>&1                   || need+=(nodejs)
# MPI sweeps (mpirun -n N shellbench sweep --study FILE; optional: the build leaves MPI out without mpicc)
command -v mpicc >/dev/null 2>&1                  || need+=(libopenmpi-dev)
command -v mpirun >/dev/null 2>&1                 || need+=(openmpi-bin)
# hypre's BoomerAMG (solver.linear=pcg-amg; optional: `make HYPRE=0` builds without)
have_hdr /usr/include/hypre/HYPRE_parcsr_ls.h     || need+=(libhypre-dev)
# `make fuzz` only (`ensure_deps.sh fuzz`): clang with libFuzzer and its sanitizer runtimes
if [ "${1:-}" = fuzz ]; then
  probe=$(mktemp -d)
  echo 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }' > "$probe/f.c"
  if ! clang -fsanitize=fuzzer,address,undefined "$probe/f.c" -o "$probe/f" >/dev/null 2>&1; then
    need+=(clang libclang-rt-dev)
  fi
  command -v clang++ >/dev/null 2>&1 || need+=(clang)
  rm -rf "$probe"
fi
if [ ${#need[@]} -eq 0 ]; then
  exit 0
fi
echo "ensure_deps: installing missing Debian packages: ${need[*]}"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${need[@]}"
echo "ensure_deps: done"
