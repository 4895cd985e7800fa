#!/usr/bin/env python3
"""vectorizer_remarks.py — which kernels PoCL's work-group vectoriser vectorised.

Reads the stderr of a seasim run made with POCL_VECTORIZER_REMARKS=1 and an empty POCL_CACHE_DIR (so
every work-group function is compiled in that run), splits LLVM's remarks per kernel (each kernel's
work-group function starts with "'_pocl_kernel_K' inlined into '_pocl_kernel_K_workgroup'"), and
prints per kernel the loop-vectoriser remarks: "vectorized loop (vectorization width: W, ...)" or
"loop not vectorized: reason". Usage: vectorizer_remarks.py LOG
"""
import re
import sys
from collections import Counter, defaultdict

text = open(sys.argv[1], errors="replace").read()
messages = [m.strip() for m in text.split("<unknown>:0:0:")]
current = None
vectorized = defaultdict(Counter)
not_vectorized = defaultdict(Counter)
for m in messages:
    k = re.match(r"'_pocl_kernel_(\w+)' inlined into '_pocl_kernel_\1_workgroup'", m)
    if k:
        current = k.group(1)
        continue
    if current is None:
        continue
    v = re.match(r"vectorized loop \((vectorization width: \d+)", m)
    if v:
        vectorized[current][v.group(1)] += 1
    n = re.match(r"loop not vectorized: (.*)", m)
    if n:
        not_vectorized[current][n.group(1)[:90]] += 1
for kernel in sorted(set(vectorized) | set(not_vectorized)):
    vec = ", ".join(f"{c}x {w}" for w, c in vectorized[kernel].items()) or "none"
    why = "; ".join(f"{c}x '{r}'" for r, c in not_vectorized[kernel].most_common(3))
    print(f"{kernel:32s} vectorised: {vec:28s} not: {why}")
