#!/usr/bin/env python3
"""fuzz_import.py OIT WORK [--count N] [--seed S] [--keep DIR] [--seed-file PATH...]:
a seeded mutation fuzzer over small OBJ, PLY, STL, glTF (text, with its .bin
beside), GLB, COLLADA, FBX, 3DS and IFC files, and the files given with
--seed-file (the suite gives a STEP and an IGES file, read by OpenCASCADE).

Every mutant goes through `oit info --model MUTANT`, which imports it in a
contained worker process (src/core/model/model_contained.c). Each run must end in
exit 0, or exit 2 with exactly one `oit: error:` line naming the file (import
warnings, `oit: warning:` lines, may come before it): never a signal, never
another status, never a timeout. The mutants are the same for a given seed,
so a failure is reproducible; --keep DIR saves the failing ones.

Mutations: flip bytes, overwrite a number with a huge, negative or
non-numeric one, delete, duplicate or insert a range, cut the file short.
"""
import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys

ASSIMP_MODELS = "/usr/share/assimp/models"
SEEDS = [
    "PLY/cube.ply",
    "PLY/cube_binary.ply",
    "PLY/cube_uv.ply",
    "PLY/float-color.ply",
    "STL/triangle.stl",
    "STL/triangle_with_two_solids.stl",
    "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
    "glTF2/BoxTextured-glTF/BoxTextured.gltf",
    "Collada/cube_triangulate.dae",
    "FBX/box.fbx",
    "3DS/cube_with_diffuse_texture.3DS",
    "OBJ/box.obj",
]
# files a seed refers to, copied once beside the mutants (a mutant's reference may break)
COMPANIONS = ["glTF2/BoxTextured-glTF/BoxTextured0.bin"]
# an OBJ of our own: groups, a material library that is missing, faces with normals
OWN_OBJ = b"""# two parts
mtllib parts.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
vn 0 0 1
o front
usemtl red
f 1//1 2//1 3//1
f 1//1 3//1 4//1
o side
f 2 6 3
f 5 6 2 1
"""
# an IFC of our own (Debian's one IFC is a 4 MB house): one extruded box in a site
OWN_IFC = b"""ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('ViewDefinition [CoordinationView]'),'2;1');
FILE_NAME('box.ifc','2024-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('IFC2X3'));
ENDSEC;
DATA;
#2=IFCPERSON($,'A',$,$,$,$,$,$);
#3=IFCORGANIZATION($,'O',$,$,$);
#4=IFCPERSONANDORGANIZATION(#2,#3,$);
#5=IFCAPPLICATION(#3,'1','oit','oit');
#6=IFCOWNERHISTORY(#4,#5,$,.ADDED.,$,$,$,0);
#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',#6,'Project',$,$,$,$,(#20),#10);
#10=IFCUNITASSIGNMENT((#11));
#11=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);
#20=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-05,#21,$);
#21=IFCAXIS2PLACEMENT3D(#22,$,$);
#22=IFCCARTESIANPOINT((0.,0.,0.));
#23=IFCLOCALPLACEMENT($,#21);
#24=IFCSITE('1YvctVUKr0kugbFTf53O9L',#6,'Site',$,$,#23,$,$,.ELEMENT.,$,$,$,$,$);
#25=IFCRELAGGREGATES('2YvctVUKr0kugbFTf53O9L',#6,$,$,#1,(#24));
#30=IFCBUILDINGELEMENTPROXY('3YvctVUKr0kugbFTf53O9L',#6,'Box',$,$,#31,#40,$,$);
#31=IFCLOCALPLACEMENT(#23,#21);
#40=IFCPRODUCTDEFINITIONSHAPE($,$,(#41));
#41=IFCSHAPEREPRESENTATION(#20,'Body','SweptSolid',(#42));
#42=IFCEXTRUDEDAREASOLID(#43,#21,#46,1.);
#43=IFCRECTANGLEPROFILEDEF(.AREA.,$,#44,2.,1.);
#44=IFCAXIS2PLACEMENT2D(#45,$);
#45=IFCCARTESIANPOINT((0.,0.));
#46=IFCDIRECTION((0.,0.,1.));
#47=IFCRELCONTAINEDINSPATIALSTRUCTURE('4YvctVUKr0kugbFTf53O9L',#6,$,$,(#30),#24);
ENDSEC;
END-ISO-10303-21;
"""
NUMBER = re.compile(rb"-?\d+(\.\d+)?")
HUGE = [b"99999999999", b"4294967295", b"2147483648", b"-1", b"-2147483649", b"nan", b"1e39", b"0", b"x"]


def mutate(data: bytes, rng: random.Random) -> bytes:
    data = bytearray(data)
    for _ in range(rng.randint(1, 3)):
        kind = rng.randrange(6)
        if not data:
            break
        if kind == 0:  # flip some bytes
            for _ in range(rng.randint(1, 8)):
                i = rng.randrange(len(data))
                data[i] = rng.randrange(256)
        elif kind == 1:  # a number becomes a hostile one
            numbers = list(NUMBER.finditer(bytes(data)))
            if numbers:
                m = rng.choice(numbers)
                data[m.start():m.end()] = rng.choice(HUGE)
        elif kind == 2:  # delete a range
            i = rng.randrange(len(data))
            del data[i:i + rng.randint(1, 64)]
        elif kind == 3:  # duplicate a range
            i = rng.randrange(len(data))
            piece = data[i:i + rng.randint(1, 64)]
            j = rng.randrange(len(data) + 1)
            data[j:j] = piece
        elif kind == 4:  # insert random bytes
            j = rng.randrange(len(data) + 1)
            data[j:j] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
        else:  # cut short
            del data[rng.randrange(len(data)):]
    return bytes(data)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("oit")
    parser.add_argument("work")
    parser.add_argument("--count", type=int, default=280)
    parser.add_argument("--seed", type=int, default=20261201)
    parser.add_argument("--keep")
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--seed-file", action="append", default=[])
    args = parser.parse_args()

    seeds = []
    for relative in SEEDS:
        path = os.path.join(ASSIMP_MODELS, relative)
        if os.path.isfile(path):
            with open(path, "rb") as f:
                seeds.append((os.path.splitext(path)[1].lower(), f.read()))
    seeds.append((".obj", OWN_OBJ))
    seeds.append((".ifc", OWN_IFC))
    for path in args.seed_file:
        with open(path, "rb") as f:
            seeds.append((os.path.splitext(path)[1].lower(), f.read()))
    if len(seeds) < 4:
        print(f"fuzz_import: too few seed files under {ASSIMP_MODELS} (Debian: assimp-testmodels)", file=sys.stderr)
        return 1

    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    for relative in COMPANIONS:
        path = os.path.join(ASSIMP_MODELS, relative)
        if os.path.isfile(path):
            shutil.copy(path, args.work)
    # the mutants are made in order (the seed decides them), then run in parallel
    rng = random.Random(args.seed)
    mutants = []
    for n in range(args.count):
        extension, data = seeds[n % len(seeds)]
        mutant = os.path.join(args.work, f"mutant_{n:04d}{extension}")
        with open(mutant, "wb") as f:
            f.write(mutate(data, rng))
        mutants.append(mutant)

    def check(mutant):
        """'ok', 'error', or why the run broke the contract."""
        try:
            run = subprocess.run([args.oit, "info", "--model", mutant], capture_output=True,
                                 timeout=args.timeout)
        except subprocess.TimeoutExpired:
            return f"no answer within {args.timeout:.0f} s"
        lines = run.stderr.decode("utf-8", "replace").splitlines()
        errors = [line for line in lines if line.startswith("oit: error:")]
        others = [line for line in lines if not line.startswith(("oit: error:", "oit: warning:"))]
        if run.returncode == 0 and not errors and not others:
            return "ok"
        if (run.returncode == 2 and len(errors) == 1 and not others and
                os.path.basename(mutant) in errors[0]):
            return "error"
        return f"exit {run.returncode}, stderr {lines[-3:]!r}"

    outcomes = {"ok": 0, "error": 0}
    failures = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        for mutant, outcome in zip(mutants, pool.map(check, mutants)):
            if outcome in outcomes:
                outcomes[outcome] += 1
                os.remove(mutant)
            else:
                failures.append((mutant, outcome))
    print(f"fuzz_import: {args.count} mutants (seed {args.seed}): {outcomes['ok']} loaded, "
          f"{outcomes['error']} refused with one line, {len(failures)} broke the contract")
    for mutant, why in failures[:10]:
        print(f"  {mutant}: {why}", file=sys.stderr)
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            shutil.copy(mutant, args.keep)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
