#!/bin/sh
# The shared library exports the dbrg_ API and nothing else (hidden visibility everywhere).
library="$1"
exported=$(nm -D --defined-only "$library" | awk '$2 ~ /^[TDBRVW]$/ {print $3}')
stray=$(printf '%s\n' "$exported" | grep -v '^dbrg_' | grep -v '^$')
if [ -n "$stray" ]; then
    echo "symbols outside the dbrg_ prefix are exported from $library:"
    printf '%s\n' "$stray"
    exit 1
fi
count=$(printf '%s\n' "$exported" | grep -c '^dbrg_')
if [ "$count" -lt 20 ]; then
    echo "only $count dbrg_ symbols exported from $library"
    exit 1
fi
echo "$count dbrg_ symbols exported, nothing else"
