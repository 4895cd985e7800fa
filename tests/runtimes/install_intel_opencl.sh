#!/usr/bin/env bash
# Installs Intel's oneAPI OpenCL CPU runtime from PyPI into a folder (nothing system-wide) and
# registers it beside the system's OpenCL drivers with an ICD folder of its own:
#   tests/runtimes/install_intel_opencl.sh DEST        (DEST: e.g. build/intel-opencl)
# then `source DEST/env.sh` and `seasim devices` lists "Intel(R) OpenCL" beside PoCL.
#
# The wheels (about 270 MB, 780 MB unpacked) are kept in a download cache that `make clean` does not
# remove: $SEASIM_WHEEL_CACHE, else $XDG_CACHE_HOME/seasim/wheels, else ~/.cache/seasim/wheels.
# A second install reads them from there without the network.
#
# Why each piece:
#  - intel-opencl-rt holds the driver (libintelocl.so) and its compiler; intel-cmplr-lib-rt the maths
#    libraries it links (libimf, libsvml, libintlc, libirng); tbb a oneTBB newer than Debian 12's
#    (libintelocl needs tbb::detail::r1 symbols that oneTBB 2021.8 lacks).
#  - The wheel's own libOpenCL.so (a second ICD loader) is left out, so the system loader (ocl-icd)
#    stays the one every program links.
#  - OCL_ICD_VENDORS names a folder holding Intel's ICD file and copies of the system's ICD files,
#    so PoCL stays visible; LD_LIBRARY_PATH puts the newer libtbb.so.12 before Debian's for the
#    whole process (seasim itself links libtbb.so.12, and one process has one libtbb).
set -euo pipefail

dest=${1:?usage: install_intel_opencl.sh DEST}
# Pinned together: the three wheels are released as a set.
packages=(intel-opencl-rt==2026.2.0 intel-cmplr-lib-rt==2026.2.0 tbb==2023.2.0)
cache=${SEASIM_WHEEL_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/seasim/wheels}
mkdir -p "$cache"

have_all() {
  local p name ver
  for p in "${packages[@]}"; do
    name=${p%%==*}; ver=${p##*==}
    ls "$cache/${name//-/_}-$ver-"*.whl >/dev/null 2>&1 || return 1
  done
}

if ! have_all; then
  command -v python3 >/dev/null || { echo "install_intel_opencl: python3 is needed to download the wheels" >&2; exit 1; }
  echo "install_intel_opencl: downloading ${packages[*]} into $cache (about 270 MB, once)"
  if ! python3 -m pip download --quiet --no-deps --only-binary=:all: -d "$cache" "${packages[@]}"; then
    echo "install_intel_opencl: cannot download the Intel OpenCL runtime from PyPI (pip download failed);" \
         "put the wheels ${packages[*]} into $cache by hand" >&2
    exit 1
  fi
fi

# Unpack into a fresh folder, then rename it into place, so a killed install leaves nothing half-made.
tmp="$dest.tmp.$$"
rm -rf "$tmp"
mkdir -p "$tmp/lib" "$tmp/vendors"
trap 'rm -rf "$tmp"' EXIT
for p in "${packages[@]}"; do
  name=${p%%==*}; ver=${p##*==}
  wheel=$(ls "$cache/${name//-/_}-$ver-"*.whl | head -1)
  python3 - "$wheel" "$tmp/lib" <<'PY'
import os, sys, zipfile
wheel, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(wheel) as z:
    for info in z.infolist():
        parts = info.filename.split("/")
        # Only the shared libraries and the driver's .rtl builtins under <name>.data/data/lib/.
        if len(parts) != 4 or parts[1:3] != ["data", "lib"] or parts[3].startswith("libOpenCL.so"):
            continue
        base = parts[3]
        with z.open(info) as src, open(os.path.join(out, base), "wb") as dst:
            dst.write(src.read())
PY
done
chmod 755 "$tmp"/lib/*.so* 2>/dev/null || true
[ -f "$tmp/lib/libintelocl.so" ] || { echo "install_intel_opencl: libintelocl.so not found in the wheels" >&2; exit 1; }

rm -rf "$dest"
mkdir -p "$(dirname "$dest")"
mv "$tmp" "$dest"
trap - EXIT
abs=$(cd "$dest" && pwd)
echo "$abs/lib/libintelocl.so" > "$abs/vendors/intel-cpu.icd"
for icd in /etc/OpenCL/vendors/*.icd; do
  [ -e "$icd" ] && cp "$icd" "$abs/vendors/"
done
cat > "$abs/env.sh" <<ENV
# source this file: seasim (and clinfo) then see Intel's OpenCL CPU runtime beside the system's drivers
export OCL_ICD_VENDORS="$abs/vendors"
export LD_LIBRARY_PATH="$abs/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
ENV
echo "install_intel_opencl: installed into $abs (source $abs/env.sh)"
