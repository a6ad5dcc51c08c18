# Install/uninstall the FRICTION-EQ package in a LAMMPS source tree
# (traditional make build: copy this folder to lammps/src/FRICTION-EQ, then
# `make yes-friction-eq` and `make mpi` in lammps/src).
# mode = 0/1/2 for uninstall/install/update
#
# The styles (*.cpp, *.h) and the LAMMPS-free kernels they use (lib/)
# are copied into src/.  lib/eq_green.* (FFTW3 + Eigen3) serves only the
# eq-green tool of the CMake build and is not copied.  The LAMMPS version,
# read from src/version.h, reaches the package's files through
# Makefile.package (FEQ_LAMMPS_VERSION, see eq_lammps_compat.h).

mode=$1

# enforce using portable C locale
LC_ALL=C
export LC_ALL

# arg1 = file in this folder (possibly lib/name), copied to ../name
action () {
  dest=../$(basename $1)
  if (test $mode = 0) then
    rm -f $dest
  elif (! cmp -s $1 $dest) then
    cp $1 $dest
    if (test $mode = 2) then
      echo "  updating src/$(basename $1)"
    fi
  fi
}

for file in *.cpp *.h lib/*.cpp lib/*.h; do
  case $file in
    lib/eq_green.*) continue ;;
  esac
  test -f ${file} && action $file
done

# FEQ_LAMMPS_VERSION in Makefile.package: YYYYMMDD of src/version.h

if (test $mode = 1 || test $mode = 2) then
  version=$(sed -n 's/^#define LAMMPS_VERSION "\([0-9]*\) \([A-Z][a-z]*\) \([0-9]*\)".*/\1 \2 \3/p' ../version.h)
  set -- $version
  month=0
  for m in Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec; do
    month=$((month + 1))
    test "$m" = "$2" && break
  done
  number=$(printf '%04d%02d%02d' $3 $month $1)
  if (test -e ../Makefile.package) then
    sed -i -e 's/[^ \t]*FEQ_LAMMPS_VERSION[^ \t]* //g' ../Makefile.package
    sed -i -e "s|^PKG_INC =[ \t]*|&-DFEQ_LAMMPS_VERSION=$number |" ../Makefile.package
  fi
  echo "  FRICTION-EQ for LAMMPS $version (FEQ_LAMMPS_VERSION=$number)"

elif (test $mode = 0) then
  if (test -e ../Makefile.package) then
    sed -i -e 's/[^ \t]*FEQ_LAMMPS_VERSION[^ \t]* //g' ../Makefile.package
  fi
fi
