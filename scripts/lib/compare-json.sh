# compare-json.sh — sourced by scripts/gpu-check and scripts/gpu-parity: the numbers they read
# from caustica's JSON (render --stats-json, compare --json) and the verdict they print.

# The number after "FIELD": in the JSON on stdin.
json_number() { sed -n "s/.*\"$1\": \([0-9.eE+-]*\|nan\|inf\).*/\1/p" | head -1; }

# The relMSE of a `caustica compare --json` result (stdin) without the image's worst 1% of
# pixels, relmse x (1 - their share), as %.6g; fails when either number is missing or not a
# number. (Where one path flipped by rounding through a specular chain puts a caustic sample in a
# dark pixel, or MLT leaves a speckle, the whole-image figure is a lottery.)
trimmed_relmse() {
    local json
    json=$(cat)
    awk -v r="$(json_number relmse <<<"$json")" -v w="$(json_number relmse_worst_1pct_share <<<"$json")" \
        'BEGIN { if (r == "" || w == "" || r + 0 != r || w + 0 != w) exit 1; printf "%.6g", r * (1 - w) }'
}

# "ok" when VALUE is a number no larger than LIMIT, else "FAIL".
verdict_within() {
    awk -v v="$1" -v limit="$2" 'BEGIN { print (v != "" && v + 0 == v && v <= limit) ? "ok" : "FAIL" }'
}
