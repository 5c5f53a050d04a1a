#!/usr/bin/env bash
# install_layout.sh BUILD_DIR WORK SCENES: an installed oit finds the shaders
# installed next to it; a wrong OIT_SHADER_DIR is refused with the path named.
source "$(dirname "$0")/lib.sh"
build=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null || fail "cmake --install"
oit=$work/prefix/bin/oit
[ -x "$oit" ] || fail "no installed oit"
shaders=$("$oit" render --model "$scenes/onion.obj" --algorithm ll --size 32x32 --json | python3 -c "import json,sys; print(json.load(sys.stdin)['shaders'])") || fail "installed oit cannot render"
case "$shaders" in
    "$work/prefix/share/oit-workbench/shaders") echo "installed oit uses $shaders" ;;
    *) fail "installed oit used $shaders, not the installed shaders" ;;
esac
OIT_SHADER_DIR=$work/nowhere expect_exit 3 "OIT_SHADER_DIR=.*nowhere.*common/oit_shared.h" -- "$oit" render --model "$scenes/onion.obj" --algorithm ll --size 32x32
