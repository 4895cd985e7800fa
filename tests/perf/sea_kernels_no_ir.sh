# sea_kernels_no_ir.sh — sourced by tests/perf/sea_internal_reflection.sh and sea_orders_fit.sh:
# kernels_no_ir DIR copies kernels/ to DIR with the path tracer's internal reflection switched off: at the
# surface from below, a reflected path ends (kernels/reference.cl) instead of mirroring. Exits when the
# line it patches has changed, so a stale patch never passes for the real path tracer.
kernels_no_ir() {
  cp -R kernels "$1"
  sed -i 's|d.y = -d.y; /\* mirror reflection at the flat surface \*/|break; /* no internal reflection */|' \
    "$1/reference.cl"
  grep -q 'break; /\* no internal reflection \*/' "$1/reference.cl" ||
    { echo "$(basename "$0"): kernels/reference.cl changed; update tests/perf/sea_kernels_no_ir.sh" >&2; exit 1; }
}
