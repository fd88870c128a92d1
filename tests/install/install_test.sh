#!/usr/bin/env bash
# Installs the built project into a prefix inside the build tree, builds examples/cpp against
# it with find_package(ltp) and checks the Floquet exponents the example prints.
# With PYTHON and PYTHON_DIR (the module's install folder, relative to the prefix), also that
# the installed Python package imports from the prefix and gives the same exponents.
# Usage: install_test.sh CMAKE BUILD_DIR EXAMPLE_DIR WORK_DIR LTP_BINARY GENERATOR CXX_COMPILER
#                        [PYTHON PYTHON_DIR]
set -euo pipefail
cmake="$1" build="$2" example="$3" work="$4" ltp="$5" generator="$6" cxx="$7"
python="${8:-}" python_dir="${9:-}"
prefix="$work/prefix"
rm -rf "$work"
mkdir -p "$work"

"$cmake" --install "$build" --prefix "$prefix"
"$cmake" -S "$example" -B "$work/example" -G "$generator" -DCMAKE_CXX_COMPILER="$cxx" \
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix"
# The package must come from the prefix, not from the build tree or a system-wide install.
grep -q "^ltp_DIR:PATH=$prefix/" "$work/example/CMakeCache.txt"
"$cmake" --build "$work/example"
"$work/example/floquet_example" | tee "$work/example.txt"

# Reference: the same analysis by the `ltp` command of this build (the example sets
# a = 1.5, q = 2, c = 0.05), as "Re Im" lines in display order.
"$ltp" floquet mathieu --set a=1.5 --set q=2 --set c=0.05 --json >"$work/reference.json"
# The objects of "exponents" are the ones with a damping_ratio.
exponents=$(tr -d ' \n' <"$work/reference.json" | grep -o '{[^{}]*"damping_ratio"[^{}]*}')
paste -d ' ' <(grep -o '"re":[^,}]*' <<<"$exponents" | cut -d: -f2) \
             <(grep -o '"im":[^,}]*' <<<"$exponents" | cut -d: -f2) >"$work/reference.txt"
cat "$work/reference.txt"

# Same code, same options: the exponents agree to round-off (the error estimate is ~1e-13),
# so 1e-9 is generous yet fails any mixed-up build. Independently of ltp, Liouville's formula
# det Φ(T) = exp(∫ tr A dt) = exp(-c T) gives Re λ1 + Re λ2 = -c exactly.
awk -v c=0.05 -v tol=1e-9 '
  function abs(x) { return x < 0 ? -x : x }
  FNR == NR { ref_re[++n] = $1; ref_im[n] = $2; next }
  /^exponent / { gsub(/[(),]/, " "); ++m; re[m] = $2; im[m] = $3; sum += $2 }
  /^error estimate / { estimate = $3 }
  END {
    if (n != 2 || m != 2) { print "expected 2 exponents, example " m ", ltp " n; exit 1 }
    for (k = 1; k <= n; ++k)
      if (abs(re[k] - ref_re[k]) > tol || abs(im[k] - ref_im[k]) > tol) {
        print "exponent " k ": example " re[k] " " im[k] ", ltp " ref_re[k] " " ref_im[k]; exit 1
      }
    if (abs(sum + c) > tol) { print "Re λ1 + Re λ2 = " sum ", Liouville: " -c; exit 1 }
    if (!(estimate >= 0 && estimate < tol)) { print "error estimate " estimate; exit 1 }
    print "install test: the installed package reproduces ltp floquet"
  }' "$work/reference.txt" "$work/example.txt"

if [[ -n "$python" ]]; then
  # Same exponents from the installed module, which must come from the prefix (not the build).
  PYTHONPATH="$prefix/$python_dir" "$python" - "$work/reference.txt" "$prefix" <<'EOF'
import sys
import ltp
assert ltp.__file__.startswith(sys.argv[2]), f"ltp imported from {ltp.__file__}"
r = ltp.floquet(ltp.scene("mathieu", a=1.5, q=2, c=0.05))
reference = [complex(*map(float, line.split())) for line in open(sys.argv[1])]
assert list(r.exponents) == reference, (list(r.exponents), reference)
print("install test: the installed Python package reproduces ltp floquet to the last digit")
EOF
fi
