#!/usr/bin/env bash
# cli_sources.sh SOURCE: the command line's sources keep their shape (issue "One shape
# for every algorithm"): src/cli includes of the core only its public oit.h (no gl_util.h,
# no GLEW or other GL header, no oit_shared.h: what the CLI needs the core offers in oit.h),
# and no file there is over 1,000 lines.
source "$(dirname "$0")/lib.sh"
cli=$1/src/cli
[ -d "$cli" ] || fail "no $cli"
status=0
for file in "$cli"/*.c "$cli"/*.h; do
    while IFS= read -r line; do
        header=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/' <<<"$line")
        case $line in
        *'"'*) [ "$header" = oit.h ] || [ -e "$cli/$header" ] ||
            { echo "$(basename "$file"): includes \"$header\", a header of neither the CLI nor oit.h" >&2; status=1; } ;;
        *) case $header in GL/* | EGL/* | GLES*/* | KHR/*)
            echo "$(basename "$file"): includes <$header>" >&2; status=1 ;; esac ;;
        esac
    done < <(grep -E '^[[:space:]]*#[[:space:]]*include' "$file")
    lines=$(wc -l <"$file")
    [ "$lines" -le 1000 ] || { echo "$(basename "$file"): $lines lines (at most 1,000)" >&2; status=1; }
done
[ "$status" -eq 0 ] || fail "src/cli's sources"
echo "src/cli: $(ls "$cli"/*.c "$cli"/*.h | wc -l) files, public core API only, none over 1,000 lines"
