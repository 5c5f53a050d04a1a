#!/usr/bin/env bash
# driver_failure.sh OIT WORK MODEL: a Gallium driver that does not exist
# (GALLIUM_DRIVER=bogus) fails context creation cleanly on both back ends: exit 3
# and one line "oit: error: ..." naming the problem, never a crash. OSMesa would
# crash inside OSMesaCreateContextAttribs (src/core/gl_context_osmesa.c); a probe
# process takes that crash, and the message names the drivers that do work. A
# driver that exists still renders through the probe. Under a tight address-space
# limit (ulimit -v) a crash in the driver or a framebuffer it cannot allocate is
# one line, exit 3. About 5 s.
set -u
. "$(dirname "$0")/lib.sh"
oit=$1 work=$2 model=$3
mkdir -p "$work"

# Mesa's failed EGL driver load leaks and then unloads the driver, so LeakSanitizer
# could only report it from an unnamed module (tests/lsan.supp names modules): leak
# detection is off for the EGL case only. The OSMesa case makes no context in this
# process (the probe child exits with _exit, before any leak check), so it keeps it.
expect_exit 3 "^oit: error: egl: .*(display|context|driver)" -- \
    env ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" GALLIUM_DRIVER=bogus \
    "$oit" render --backend egl --model "$model" --size 16x16 --out "$work/egl.png"
[ ! -e "$work/egl.png" ] || fail "egl wrote an image without a context"

expect_exit 3 "^oit: error: osmesa: GALLIUM_DRIVER=bogus is no driver this OSMesa can create a context with \(creating one crashed a probe process: .*\); drivers that can: .*llvmpipe" -- \
    env GALLIUM_DRIVER=bogus "$oit" render --backend osmesa --model "$model" --size 16x16 --out "$work/osmesa.png"
[ ! -e "$work/osmesa.png" ] || fail "osmesa wrote an image without a context"

# the same through a debug context (stderr is not captured there)
expect_exit 3 "^oit: error: osmesa: GALLIUM_DRIVER=bogus is no driver" -- \
    env GALLIUM_DRIVER=bogus "$oit" render --backend osmesa --debug --model "$model" --size 16x16 \
    --out "$work/osmesa-debug.png"

# a driver OSMesa has: the probe lets it through and the frame renders
GALLIUM_DRIVER=llvmpipe "$oit" render --backend osmesa --model "$model" --size 16x16 \
    --out "$work/llvmpipe.png" >/dev/null || fail "GALLIUM_DRIVER=llvmpipe does not render on osmesa"
"$oit" render --backend osmesa --model "$model" --size 16x16 --out "$work/default.png" >/dev/null \
    || fail "osmesa does not render without GALLIUM_DRIVER"
"$oit" compare "$work/llvmpipe.png" "$work/default.png" >/dev/null \
    || fail "GALLIUM_DRIVER=llvmpipe renders a different image"

# the driver out of memory: a tight address-space limit (ulimit -v) can make Mesa's
# shader compiler crash on EGL: one line and exit 3 (or a clean error, or a frame),
# never a bare signal. (Not under AddressSanitizer, whose shadow memory needs
# terabytes of address space.)
if [ -z "${ASAN_OPTIONS:-}" ]; then
    for backend in egl osmesa; do
        status=0
        ( ulimit -v 300000; exec "$oit" render --backend "$backend" --model "$model" --size 64x64 \
              --out "$work/tight-$backend.png" ) >/dev/null 2>"$work/tight.err" || status=$?
        lines=$(wc -l <"$work/tight.err")
        if [ "$status" -ne 0 ] && { [ "$status" -ne 3 ] || [ "$lines" -ne 1 ] || ! grep -q "^oit: error: " "$work/tight.err"; }; then
            cat "$work/tight.err" >&2
            fail "ulimit -v 300000, $backend: exit $status with $lines line(s), not 0 or 3 with one line"
        fi
        echo "ok ($status): ulimit -v 300000, $backend: $(cat "$work/tight.err")"
    done
else
    echo "skipped under ASan: the tight address-space limit"
fi
# a frame whose targets the driver cannot allocate: the error names the framebuffer (every
# algorithm as "NAME: the WHAT framebuffer", oit_gpu_framebuffer), the
# size and the memory it needed, not only "incomplete (0x8cd6)"
if [ -z "${ASAN_OPTIONS:-}" ]; then
    expect_exit 3 "^oit: error: blend: the accumulation framebuffer is incomplete \(GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT, 0x8cd6\): the driver could not allocate its textures at 16384x16384, the frame's textures and buffers needing 5.00 GiB in all" -- \
        bash -c 'ulimit -v 2000000; exec "$@"' _ "$oit" render --algorithm blend --model "$model" --size 16384x16384 \
        --out "$work/huge.png"
    [ ! -e "$work/huge.png" ] || fail "an image was written for a frame without targets"
else
    echo "skipped under ASan: the 16384x16384 frame under ulimit -v"
fi
echo "driver failures: ok"
