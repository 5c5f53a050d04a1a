#!/usr/bin/env bash
# core_layers.sh SOURCE: the model's layers and the reference's independence keep
# their shape (issue "One shape for every algorithm"; docs/architecture.md):
# - Assimp's headers only in model_assimp.c (the importer) and model_obj.cpp (its
#   number reader, assimp/fast_atof.h): the finishing (model_finish.c,
#   model_planes.c) and the import's own checks (model_import.c) include none;
# - OpenCASCADE's headers (*.hxx) only in model_occt.cpp (the STEP and IGES reader);
# - the finishing includes nothing of the import (model_obj.h);
# - the reference (alg_reference.c, reference_raster.c, pick.c, reference_internal.h)
#   includes of the core only oit.h, capabilities.h, oit_shared.h (definitions) and
#   reference_internal.h, which nothing else includes: no GPU-side helper;
# - no file in src/core/model or of the reference is over 1,000 lines.
source "$(dirname "$0")/lib.sh"
shopt -s nullglob
core=$1/src/core
[ -d "$core/model" ] || fail "no $core/model"
status=0
complain() { echo "$*" >&2; status=1; }
includes() { sed -nE 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/p' "$1"; }

for file in "$core"/model/* "$core"/*.c "$core"/*.cpp "$core"/*.h; do
    name=$(basename "$file")
    for header in $(includes "$file"); do
        case $header in
        assimp/*)
            case $name:$header in
            model_assimp.c:* | model_obj.cpp:assimp/fast_atof.h) ;;
            *) complain "$name: includes <$header> (Assimp belongs to model_assimp.c)" ;;
            esac ;;
        *.hxx)
            [ "$name" = model_occt.cpp ] || complain "$name: includes <$header> (OpenCASCADE belongs to model_occt.cpp)" ;;
        model_obj.h)
            case $name in model_finish.c | model_planes.c) complain "$name: includes $header (the finishing reads no file)" ;; esac ;;
        reference_internal.h)
            case $name in alg_reference.c | reference_raster.c | pick.c) ;; *) complain "$name: includes $header (the reference's own)" ;; esac ;;
        esac
    done
done
for file in "$core"/alg_reference.c "$core"/reference_raster.c "$core"/pick.c "$core"/reference_internal.h; do
    for header in $(includes "$file"); do
        [ -e "$core/$header" ] || [ -e "$1/shaders/common/$header" ] || continue # a system header
        case $header in
        oit.h | capabilities.h | oit_shared.h | reference_internal.h) ;;
        *) complain "$(basename "$file"): includes $header: the oracle shares no computation with what it checks" ;;
        esac
    done
done
for file in "$core"/model/* "$core"/alg_reference.c "$core"/reference_raster.c "$core"/pick.c "$core"/reference_internal.h; do
    lines=$(wc -l <"$file")
    [ "$lines" -le 1000 ] || complain "$(basename "$file"): $lines lines (at most 1,000)"
done
[ "$status" -eq 0 ] || fail "src/core's layers"
echo "src/core: Assimp in model_assimp.c (and model_obj.cpp's number reader) only, OpenCASCADE in model_occt.cpp only, the finishing and the reference apart, $(ls "$core"/model | wc -l) model files and the reference's 3 under 1,000 lines"
