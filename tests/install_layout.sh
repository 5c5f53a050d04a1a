#!/usr/bin/env bash
# install_layout.sh BUILD_DIR WORK SCENES [WORKBENCH_BUILT]: `cmake --install` to
# a temporary prefix. The installed oit finds the shaders installed next to it; a
# wrong OIT_SHADER_DIR is refused with the path named. When the workbench was
# built (WORKBENCH_BUILT=1): its desktop entry and icon are installed and resolve
# to the installed program and icon, and the installed oit-workbench renders
# under Xvfb, on its default model and on one named, from the prefix alone.
# Where a private mount namespace is available (unshare), the installed programs
# run with the source tree's shaders/, resources/ and config/ hidden under empty
# tmpfs mounts, so a fallback to the source tree would fail instead of passing.
source "$(dirname "$0")/lib.sh"
build=$1 work=$2 scenes=$3 workbench_built=${4:-0}
src=$(cd "$(dirname "$0")/.." && pwd)
unset OIT_SHADER_DIR # the installed layout alone decides
rm -rf "$work"; mkdir -p "$work"
work=$(cd "$work" && pwd -P)
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null || fail "cmake --install"
cd "$work" || fail "cannot cd to $work"

# "${hidden[@]}" COMMAND...: COMMAND with the source tree's data directories
# hidden, in a private mount namespace (nothing outside it sees the mounts)
hide_script='for d in "$0/shaders" "$0/resources" "$0/config"; do
    [ ! -d "$d" ] || mount -t tmpfs -o ro oit-hidden "$d" || exit 125
done
[ ! -e "$0/shaders/common/oit_shared.h" ] || { echo "the source shaders are still visible" >&2; exit 125; }
exec "$@"'
hidden=()
for flags in -m -rm; do
    if unshare "$flags" --propagation private bash -c "$hide_script" "$src" true 2>/dev/null; then
        hidden=(unshare "$flags" --propagation private bash -c "$hide_script" "$src")
        echo "installed programs run with $src/{shaders,resources,config} hidden (unshare $flags)"
        break
    fi
done
[ ${#hidden[@]} -gt 0 ] || echo "no private mount namespace (unshare): the source tree stays visible; only the reported paths are checked"

oit=$prefix/bin/oit
[ -x "$oit" ] || fail "no installed oit"
shaders=$("$oit" render --model "$scenes/onion.obj" --algorithm ll --size 32x32 --json | python3 -c "import json,sys; print(json.load(sys.stdin)['shaders'])") || fail "installed oit cannot render"
case "$shaders" in
    "$prefix/share/oit-workbench/shaders") echo "installed oit uses $shaders" ;;
    *) fail "installed oit used $shaders, not the installed shaders" ;;
esac
OIT_SHADER_DIR=$work/nowhere expect_exit 3 "OIT_SHADER_DIR=.*nowhere.*common/oit_shared.h" -- "$oit" render --model "$scenes/onion.obj" --algorithm ll --size 32x32
# the same render with the source tree's shaders out of reach
shaders=$("${hidden[@]}" "$oit" render --model "$scenes/onion.obj" --algorithm ll --size 32x32 --json | python3 -c "import json,sys; print(json.load(sys.stdin)['shaders'])") \
    || fail "installed oit cannot render without the source tree"
[ "$shaders" = "$prefix/share/oit-workbench/shaders" ] || fail "without the source tree, installed oit used $shaders"

# no installed program keeps a run-time search path into the build or source tree
if command -v readelf >/dev/null; then
    for program in "$prefix"/bin/*; do
        runpath=$(readelf -d "$program" | grep -E "R(UN)?PATH" || true)
        case "$runpath" in
            *"$build"* | *"$src"*) fail "$program keeps a search path into the build: $runpath" ;;
        esac
    done
fi

if [ "$workbench_built" != 1 ]; then
    echo "oit-workbench not built (no Qt 5): workbench, desktop entry and icon not checked"
    echo "install layout: ok"
    exit 0
fi

# The workbench, its data, desktop entry and icon.
workbench=$prefix/bin/oit-workbench
desktop=$prefix/share/applications/oit-workbench.desktop
icon=$prefix/share/icons/hicolor/scalable/apps/oit-workbench.svg
[ -x "$workbench" ] || fail "no installed oit-workbench"
[ -f "$desktop" ] || fail "no installed desktop entry $desktop"
[ -f "$icon" ] || fail "no installed icon $icon"
[ -f "$prefix/share/oit-workbench/resources/models/gearbox.obj" ] || fail "no installed default model"
[ -f "$prefix/share/oit-workbench/config/models.json" ] || fail "no installed config/models.json"

# The desktop entry's keys; Exec and Icon resolve inside the prefix; every MIME
# type is one shared-mime-info knows; the icon is an SVG; the bundled entries of
# the models list exist in the prefix.
resolved=$(python3 - "$desktop" "$prefix" <<'PY'
import configparser, json, os, shlex, shutil, sys
import xml.etree.ElementTree as ET

desktop, prefix = sys.argv[1], sys.argv[2]
def fail(message):
    sys.exit(f"FAIL: {desktop}: {message}")

with open(desktop, encoding="utf-8") as f:
    lines = [line.rstrip("\n") for line in f]
first = next((line for line in lines if line.strip() and not line.startswith("#")), "")
if first != "[Desktop Entry]":
    fail(f"the first group is {first!r}, not [Desktop Entry]")
parser = configparser.ConfigParser(interpolation=None, strict=True, delimiters=("=",))
parser.optionxform = str  # keys are case-sensitive
parser.read_string("\n".join(lines))
entry = parser["Desktop Entry"]
for key in ("Type", "Name", "GenericName", "Comment", "Exec", "Icon", "Terminal", "Categories", "MimeType"):
    if not entry.get(key, "").strip():
        fail(f"no {key}")
if entry["Type"] != "Application":
    fail(f"Type={entry['Type']}")
if entry["Terminal"] != "false":
    fail(f"Terminal={entry['Terminal']}")
for key in ("Categories", "MimeType", "Keywords"):
    if key in entry and not entry[key].endswith(";"):
        fail(f"{key} does not end with ';'")
categories = entry["Categories"].rstrip(";").split(";")
main = {"AudioVideo", "Audio", "Video", "Development", "Education", "Game", "Graphics", "Network",
        "Office", "Science", "Settings", "System", "Utility"}
if not main & set(categories):
    fail(f"no main category in {categories}")
if "3DGraphics" in categories and "Graphics" not in categories:
    fail("3DGraphics without Graphics")

mime_dir = "/usr/share/mime"
# the types the prefix declares itself (share/mime/packages/*.xml: sessions' application/x-oit-session)
ns = "{http://www.freedesktop.org/standards/shared-mime-info}"
own = {}
packages = os.path.join(prefix, "share", "mime", "packages")
for name in sorted(os.listdir(packages)) if os.path.isdir(packages) else []:
    root = ET.parse(os.path.join(packages, name)).getroot()
    if root.tag != ns + "mime-info":
        fail(f"{packages}/{name} is not a shared-mime-info package")
    for mime in root.findall(ns + "mime-type"):
        own[mime.get("type")] = [g.get("pattern") for g in mime.findall(ns + "glob")]
if "application/x-oit-session" in entry["MimeType"].split(";") and own.get("application/x-oit-session") != ["*.oitsession"]:
    fail("MimeType lists application/x-oit-session but no installed share/mime/packages/*.xml declares it with *.oitsession")
if os.path.isfile(f"{mime_dir}/types"):
    known = set(open(f"{mime_dir}/types").read().split()) | set(own)
    if os.path.isfile(f"{mime_dir}/aliases"):
        known |= {line.split()[0] for line in open(f"{mime_dir}/aliases") if line.strip()}
    for mime in entry["MimeType"].rstrip(";").split(";"):
        if mime not in known:
            fail(f"MimeType {mime} is not in shared-mime-info's database")

exec_args = shlex.split(entry["Exec"])
codes = [a for a in exec_args[1:] if a.startswith("%")]
if len(codes) != 1 or codes[0] not in ("%f", "%F", "%u", "%U"):
    fail(f"Exec={entry['Exec']}: expected one file field code")
bin_dir = os.path.join(prefix, "bin")
for key, program in (("Exec", exec_args[0]), ("TryExec", entry.get("TryExec", exec_args[0]))):
    path = program if os.path.isabs(program) else shutil.which(program, path=bin_dir)
    if not path or not os.path.samefile(path, os.path.join(bin_dir, "oit-workbench")):
        fail(f"{key} program {program!r} is not {bin_dir}/oit-workbench")

icon = entry["Icon"]
if os.path.isabs(icon) or "/" in icon or icon.endswith((".svg", ".png")):
    fail(f"Icon={icon}: a theme icon name is expected")
theme = os.path.join(prefix, "share", "icons", "hicolor")
found = [os.path.join(root, name) for root, _, names in os.walk(theme) for name in names
         if os.path.splitext(name)[0] == icon and root.endswith("/apps")]
if not found:
    fail(f"Icon={icon} is not under {theme}/*/apps")
for path in found:
    if path.endswith(".svg"):
        root = ET.parse(path).getroot()
        if root.tag != "{http://www.w3.org/2000/svg}svg" or "viewBox" not in root.attrib:
            fail(f"{path} is not an SVG with a viewBox")

share = os.path.join(prefix, "share", "oit-workbench")
for model in json.load(open(os.path.join(share, "config", "models.json")))["models"]:
    if not model["path"].startswith("/") and not os.path.isfile(os.path.join(share, model["path"])):
        fail(f"models.json's {model['name']} ({model['path']}) is not installed")
print(shutil.which(exec_args[0], path=bin_dir), *found)
PY
) || fail "desktop entry, icon or models list"
echo "desktop entry: Exec and Icon resolve to $resolved"
if command -v desktop-file-validate >/dev/null; then
    desktop-file-validate "$desktop" || fail "desktop-file-validate $desktop"
    echo "desktop-file-validate: ok"
else
    echo "desktop-file-validate not installed (Debian: desktop-file-utils): skipped; keys checked above"
fi

# --help from the prefix, without a display
env -u DISPLAY -u WAYLAND_DISPLAY "$workbench" --help | grep -q -- "--screenshot" \
    || fail "installed oit-workbench --help does not list --screenshot"

if ! command -v xvfb-run >/dev/null; then
    echo "xvfb-run not installed (Debian: xvfb, xauth): the installed workbench is not started"
    echo "install layout: ok"
    exit 0
fi
mkdir -p "$work/config" "$work/runtime" && chmod 700 "$work/runtime"

# png_check FILE MIN_W MIN_H: a PNG at least that large with more than a few colours
png_check() {
    python3 - "$@" <<'PY'
import struct, sys, zlib
path, min_w, min_h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
data = open(path, "rb").read()
if data[:8] != b"\x89PNG\r\n\x1a\n":
    sys.exit(f"FAIL: {path} is not a PNG")
pos, idat, ihdr = 8, b"", None
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    if kind == b"IHDR":
        ihdr = struct.unpack(">IIBBBBB", body)
    elif kind == b"IDAT":
        idat += body
    pos += 12 + length
width, height, depth, colour, _, _, interlace = ihdr
if width < min_w or height < min_h:
    sys.exit(f"FAIL: {path} is {width}x{height}, smaller than {min_w}x{min_h}")
channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
if depth != 8 or channels is None or interlace:
    print(f"{path}: {width}x{height} (depth {depth}, colour type {colour}: colours not counted)")
    sys.exit(0)
raw, stride = zlib.decompress(idat), width * channels
previous, colours = bytearray(stride), set()
for y in range(height):
    kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - channels] if i >= channels else 0
        b, c = previous[i], previous[i - channels] if i >= channels else 0
        if kind == 1: line[i] = (line[i] + a) & 255
        elif kind == 2: line[i] = (line[i] + b) & 255
        elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    colours.update(bytes(line[i:i + channels]) for i in range(0, stride, channels))
    previous = line
if len(colours) < 16:
    sys.exit(f"FAIL: {path} has only {len(colours)} colours")
print(f"{path}: {width}x{height}, {len(colours)} colours")
PY
}

# run_workbench ARGS...: the installed workbench under its own Xvfb, from $work
run_workbench() {
    timeout 600 xvfb-run -a -s "-screen 0 1280x1024x24" \
        env DBUS_SESSION_BUS_ADDRESS=disabled: XDG_CONFIG_HOME="$work/config" XDG_RUNTIME_DIR="$work/runtime" \
            QT_QPA_PLATFORM=xcb "${hidden[@]}" "$workbench" "$@"
}

# no model: the installed default gearbox
run_workbench --size 160x120 --screenshot "$work/shot.png" > "$work/shot.txt" 2> "$work/shot.err" \
    || { cat "$work/shot.err" >&2; fail "installed oit-workbench did not render its default model"; }
grep -q "shot.png" "$work/shot.txt" || fail "installed oit-workbench printed no screenshot path"
png_check "$work/shot.png" 160 120 || fail "screenshot of the default model"

# a model named on the command line, from the prefix's resources
model=$prefix/share/oit-workbench/resources/models/gearbox.obj
run_workbench "$model" --algorithm dp --size 160x120 --screenshot "$work/named.png" > /dev/null 2> "$work/named.err" \
    || { cat "$work/named.err" >&2; fail "installed oit-workbench did not render $model"; }
png_check "$work/named.png" 160 120 || fail "screenshot of $model"
echo "install layout: ok"
