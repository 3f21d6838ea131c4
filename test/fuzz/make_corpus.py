#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets: test/fuzz/corpus/<target>/seed-*.

Every seed is built field by field in the byte layout that fuzz_input.h decodes
(each field has a fixed length), one or more per mode and hard configuration:
touching, coplanar, coaxial, nearly parallel down to 1e-12 rad, one disk at the
other's rim, far from the origin (1e9), tiny and huge radii, and raw IEEE
patterns (NaN, inf, denormals, non-orthonormal rotations). fuzz_hook's seeds
carry one more byte, the target's option byte. fuzz_disk_environment has its own
layout (a geometry byte, a flags byte, then fractions): its seeds are every
geometry kind under each flag combination with fixed pseudo-random fractions.

    python3 test/fuzz/make_corpus.py      # rewrites the seed-* files, deterministic
"""
import math
import pathlib
import random
import struct

TARGETS = ["fuzz_exact_distance", "fuzz_almohamad_selim", "fuzz_disk_intersection", "fuzz_hook"]
MODES = ["generic", "coplanar", "parallel", "coaxial", "near_parallel", "shared_point",
         "rim_on_face", "centre_on_rim", "raw"]
CORPUS = pathlib.Path(__file__).resolve().parent / "corpus"


def u8(v):
    return bytes([v & 0xFF])


def u16(v):
    return struct.pack("<H", max(0, min(0xFFFF, int(v))))


def fraction(x):
    return u16(round(max(0.0, min(1.0, x)) * 65535))


def magnitude(value):
    """fuzz_input.h magnitude(): 3 bytes."""
    eighths = value * 8
    if eighths == int(eighths) and 1 <= eighths <= 32:
        return u8(int(eighths) - 1) + u16(0)
    value = min(max(value, 1e-9), 1e9)
    mantissa, exponent = math.frexp(value)  # value = mantissa 2^exponent, mantissa in [0.5, 1)
    mantissa, exponent = 2 * mantissa, exponent - 1
    exponent = max(-30, min(30, exponent))
    byte = next(b for b in range(32, 256) if -30 + (b - 32) * 61 // 224 == exponent)
    return u8(byte) + u16(round((mantissa - 1) * 65536))


def coordinate(value):
    """fuzz_input.h coordinate(): 4 bytes; sign bytes < 64 mean 0."""
    if value == 0:
        return u8(0) + magnitude(1.0)
    return u8(65 if value < 0 else 64) + magnitude(abs(value))


def point(x, y, z):
    return coordinate(x) + coordinate(y) + coordinate(z)


def angle(theta):
    return fraction((theta % (2 * math.pi)) / (2 * math.pi))


def signed_gap(value):
    if value == 0:
        return u8(0) + u16(0)
    return u8(65 if value < 0 else 64) + fraction((math.log10(abs(value)) + 16) / 25)


def tilt(value):
    return u8(1 if value < 0 else 0) + fraction((math.log10(abs(value)) + 12) / 11)


def permutation(index):
    """One of the signed permutation matrices (exact entries); 9 bytes."""
    return u8(0) + u16(index) + u16(0) * 3


def quaternion(w, x, y, z):
    norm = max(abs(w), abs(x), abs(y), abs(z))
    parts = [round(c / norm * 32767) & 0xFFFF for c in (w, x, y, z)]
    return u8(1) + b"".join(u16(p) for p in parts)


def random_rotation(rng):
    return quaternion(*(rng.uniform(-1, 1) for _ in range(4)))


IDENTITY = permutation(0)


def header(mode, r1, r2, R_W1, c1):
    return u8(MODES.index(mode)) + magnitude(r1) + magnitude(r2) + R_W1 + point(*c1)


def seeds():
    rng = random.Random(20240601)
    far = (1e9, -1e9, 1e9)
    out = {}

    def add(name, data):
        out[name] = data

    # generic: independent poses.
    add("generic-perpendicular", header("generic", 1, 1, IDENTITY, (0, 0, 0)) +
        permutation(8) + point(0.5, 0, 0.25))
    add("generic-random", header("generic", 0.75, 1.5, random_rotation(rng), (1, -2, 0.5)) +
        random_rotation(rng) + point(0.625, -1.25, 0.875))
    add("generic-tiny-huge", header("generic", 1e-9, 1e9, random_rotation(rng), (0, 0, 0)) +
        random_rotation(rng) + point(3e8, 1e-9, -2e8))
    add("generic-far", header("generic", 0.5, 2, random_rotation(rng), far) +
        random_rotation(rng) + point(1, 2, -1))
    add("generic-tiny-disks", header("generic", 1e-9, 2e-9, random_rotation(rng), (0, 0, 0)) +
        random_rotation(rng) + point(1e-9, 3e-9, 0))

    # coplanar: D = |r1 + r2 + gap| along `direction`, disk 2 turned by phi (and flipped).
    def coplanar(name, r1, r2, gap, c1=(0, 0, 0), flip=0, R=IDENTITY):
        add(name, header("coplanar", r1, r2, R, c1) + angle(0.3) + signed_gap(gap) + angle(1.1) + u8(flip))
    coplanar("coplanar-touching", 1, 0.5, 0)
    coplanar("coplanar-apart-1e-16", 1, 1, 1e-16, R=random_rotation(rng))
    coplanar("coplanar-overlap-1e-12", 1, 1, -1e-12, flip=1)
    coplanar("coplanar-contained", 2, 0.5, -2.4)
    coplanar("coplanar-far-touching", 1, 1, 0, c1=far, R=random_rotation(rng))

    # parallel: as coplanar plus a height.
    def parallel(name, r1, r2, gap, height, c1=(0, 0, 0), R=IDENTITY):
        add(name, header("parallel", r1, r2, R, c1) + angle(2.0) + signed_gap(gap) + angle(0.4) +
            u8(0) + signed_gap(height))
    parallel("parallel-stacked", 1, 1, -1.9, 1e-3)
    parallel("parallel-stacked-1e-16", 1, 0.5, -1.2, 1e-16, R=random_rotation(rng))
    parallel("parallel-edge-touching", 1, 1, 0, 1e-9)
    parallel("parallel-far", 3, 1, 1e-6, -1e-6, c1=far, R=random_rotation(rng))

    # coaxial: disk 2's centre on disk 1's axis.
    def coaxial(name, r1, r2, height, flip=0, c1=(0, 0, 0), R=IDENTITY):
        add(name, header("coaxial", r1, r2, R, c1) + coordinate(height) + angle(0.7) + u8(flip))
    coaxial("coaxial-coincident", 1, 1, 0)
    coaxial("coaxial-1e-9", 1, 0.5, 1e-9, flip=1, R=random_rotation(rng))
    coaxial("coaxial-far", 2, 2, 1e9, c1=far, R=random_rotation(rng))

    # near_parallel: tilt about an in-plane axis, lateral gap, height.
    def near_parallel(name, tilt_angle, lateral, height, r1=1, r2=1, c1=(0, 0, 0), R=IDENTITY):
        add(name, header("near_parallel", r1, r2, R, c1) + tilt(tilt_angle) + angle(0.9) + angle(2.5) +
            angle(4.0) + signed_gap(lateral) + signed_gap(height))
    near_parallel("near-parallel-1e-12-stacked", 1e-12, -1.5, 1e-9)
    near_parallel("near-parallel-1e-12-side", -1e-12, 1e-9, 1e-12, R=random_rotation(rng))
    near_parallel("near-parallel-1e-9-rim", 1e-9, 1e-12, 0, r2=0.5)
    near_parallel("near-parallel-1e-6", 1e-6, -0.5, 1e-6, R=random_rotation(rng))
    near_parallel("near-parallel-1e-3-far", 1e-3, 0.25, -1e-4, c1=far, R=random_rotation(rng))
    near_parallel("near-parallel-huge", 1e-8, 1e3, 1e-3, r1=1e9, r2=1e8)

    # shared_point: kind bit 0 = on rim 1, bit 1 = on rim 2.
    def shared(name, kind, rho1, alpha, R12, rho2, beta, c1=(0, 0, 0), R=IDENTITY):
        add(name, header("shared_point", 1, 0.75, R, c1) + u8(kind) + fraction(rho1) + angle(alpha) +
            R12 + fraction(rho2) + angle(beta))
    shared("shared-rim-rim-perpendicular", 3, 1, 0.0, permutation(8), 1, 0.0)
    shared("shared-rim-rim", 3, 1, 1.0, random_rotation(rng), 1, 2.0, R=random_rotation(rng))
    shared("shared-rim-face", 2, 0.5, 0.5, random_rotation(rng), 1, 4.0)
    shared("shared-face-face", 0, 0.3, 2.0, random_rotation(rng), 0.6, 1.0)
    shared("shared-far", 3, 1, 3.0, random_rotation(rng), 1, 5.0, c1=far, R=random_rotation(rng))

    # rim_on_face: kind bit 0 = tilt from tilt() (tiny), else fraction * pi/2;
    # bit 1 = the point on disk 1's rim.
    def rim_on_face(name, kind, tilt_angle, tilt_fraction, rho, gap, c1=(0, 0, 0), R=IDENTITY):
        add(name, header("rim_on_face", 1, 0.5, R, c1) + u8(kind) + tilt(tilt_angle) +
            fraction(tilt_fraction) + angle(1.3) + fraction(rho) + angle(0.2) + signed_gap(gap))
    rim_on_face("rim-on-face-touching", 0, 1e-3, 0.5, 0.5, 0)
    rim_on_face("rim-on-face-1e-16", 0, 1e-3, 0.25, 0.9, 1e-16, R=random_rotation(rng))
    rim_on_face("rim-on-face-vertical", 0, 1e-3, 1.0, 0.2, 1e-6)
    rim_on_face("rim-on-face-tilt-1e-12", 1, 1e-12, 0, 0.5, 1e-9)
    rim_on_face("rim-on-face-at-rim", 2, 1e-3, 0.6, 0, 0)
    rim_on_face("rim-on-face-crossing", 0, 1e-3, 0.3, 0.5, -1e-12)
    rim_on_face("rim-on-face-far", 3, 1e-7, 0, 0, 1e-12, c1=far, R=random_rotation(rng))

    # centre_on_rim: disk 2's centre on disk 1's rim.
    add("centre-on-rim-perpendicular", header("centre_on_rim", 1, 1, IDENTITY, (0, 0, 0)) + angle(0) +
        permutation(8))
    add("centre-on-rim-random", header("centre_on_rim", 2, 0.5, random_rotation(rng), (1, 1, 1)) +
        angle(2) + random_rotation(rng))
    add("centre-on-rim-far", header("centre_on_rim", 1e-3, 1e3, random_rotation(rng), far) + angle(5) +
        random_rotation(rng))

    # raw: flags bits 0..5 = r1, r2, R_W1, R_W2, c1, c2 raw; bit 6 inject a
    # special value; bit 7 perturb a rotation. Raw fields are little-endian
    # doubles here (the float decoding reads the same bytes as floats).
    def raw_double(x):
        return struct.pack("<d", x)
    valid_fields = magnitude(1) + magnitude(0.5) + random_rotation(rng) + random_rotation(rng) + \
        point(0, 0, 0) + point(0.25, 0.5, 0.75)
    for slot, value in [(0, 0), (1, 1), (2, 2), (10, 0), (11, 3), (19, 1), (20, 0), (23, 2),
                        (25, 0), (0, 4), (21, 5), (24, 6), (13, 7)]:
        add(f"raw-inject-slot{slot}-value{value}", u8(8) + u8(0x40) + valid_fields + u8(slot) + u8(value))
    for which, size in [(0, 0), (1, 120), (0, 160), (1, 200), (0, 255)]:
        add(f"raw-perturbed-rotation{which}-eps{size}", u8(8) + u8(0x80) + valid_fields + u8(which) +
            u8(size) + bytes(rng.randrange(256) for _ in range(9)))
    nan, inf = float("nan"), float("inf")
    identity = [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0]
    all_raw = lambda r1, r2, R1, R2, c1, c2: u8(8) + u8(0x3F) + b"".join(
        raw_double(v) for v in [r1, r2, *R1, *R2, *c1, *c2])
    add("raw-all-identity", all_raw(1, 1, identity, identity, (0, 0, 0), (0, 0, 1)))
    add("raw-nan-translation", all_raw(1, 1, identity, identity, (nan, 0, 0), (0, 0, 1)))
    add("raw-inf-rotation", all_raw(1, 1, identity, [inf] + identity[1:], (0, 0, 0), (0, 0, 1)))
    add("raw-denormal-radii", all_raw(5e-324, 5e-324, identity, identity, (0, 0, 0), (0, 0, 1e-323)))
    add("raw-huge", all_raw(1e300, 1e300, identity, identity, (-1e308, 0, 0), (1e308, 0, 0)))
    add("raw-scaled-rotation", all_raw(1, 1, [2 * v for v in identity], identity, (0, 0, 0), (0, 0, 1)))
    add("raw-zero-rotation", all_raw(1, 1, [0.0] * 9, identity, (0, 0, 0), (0, 0, 1)))
    add("raw-negative-radius", all_raw(-1, 1, identity, identity, (0, 0, 0), (0, 0, 1)))
    add("raw-random", u8(8) + bytes(rng.randrange(256) for _ in range(200)))
    return out


def environment_seeds():
    """fuzz_disk_environment: kinds 0-7 (mesh BV types) and 8 (octree), flags
    for float, disk first, indep solver and raw mode, 200 fixed random bytes."""
    out = {}
    for kind in range(9):
        for flags in (0x00, 0x01, 0x02, 0x04, 0x07, 0x70, 0x73):
            rng = random.Random(kind * 256 + flags)
            body = bytes(rng.randrange(256) for _ in range(200))
            out[f"kind{kind}-flags{flags:02x}"] = u8(kind) + u8(flags) + body
    return out


def main():
    directory = CORPUS / "fuzz_disk_environment"
    directory.mkdir(parents=True, exist_ok=True)
    for old in directory.glob("seed-*"):
        old.unlink()
    for name, data in sorted(environment_seeds().items()):
        (directory / f"seed-{name}").write_bytes(data)
    all_seeds = seeds()
    for target in TARGETS:
        directory = CORPUS / target
        directory.mkdir(parents=True, exist_ok=True)
        for old in directory.glob("seed-*"):
            old.unlink()
        for index, (name, data) in enumerate(sorted(all_seeds.items())):
            if target == "fuzz_hook":
                data += u8(index % 12)  # method, signed request, broadphase chain length
            (directory / f"seed-{name}").write_bytes(data)
    print(f"{len(all_seeds)} seeds in each of {len(TARGETS)} targets under {CORPUS}")


if __name__ == "__main__":
    main()
