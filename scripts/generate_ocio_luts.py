#!/usr/bin/env python3
"""Generates the data files of Velvet's shipped OpenColorIO config (resources/ocio/).

    scripts/generate_ocio_luts.py            # writes resources/ocio/luts/agx_base_sigmoid.spi1d
    scripts/generate_ocio_luts.py --matrices # prints the RGB <-> XYZ matrices used in config.ocio

Standard library only, deterministic output: running it again must give a byte-identical file.

AgX sigmoid
-----------
The "AgX" view of config.ocio is the minimal AgX of Sobotka's AgX base as published by Benjamin
Wrensch ("Minimal AgX implementation", iolite-engine.com, 2023): inset matrix -> log2 encoding
between -12.47393 and +4.026069 EV around 1.0 -> a 6th-order polynomial fit of the AgX "default
contrast" sigmoid -> outset matrix -> decode with a 2.2 power. OCIO 2.1 has no built-in transform for
the polynomial, so it is tabulated here as a 1D LUT on [0, 1] (Sony Pictures Imageworks .spi1d
format, which OCIO reads natively). The matrices and the log2 allocation stay in the config itself.

Linear interpolation error of the LUT: |f''| <= 7.5 on [0, 1], h = 1/(N-1), error <= h^2 |f''| / 8,
about 1e-6 for N = 1024, far below 1/255. 1024 entries also fit one row of a GPU texture, so OCIO's
shader samples it as a 1D texture (4096 entries become a 4096x2 2D texture in OCIO 2.1).

Matrices
--------
Normalised primary matrices (SMPTE RP 177-1993) from the primaries and white points of
ITU-R BT.709-6 (sRGB, IEC 61966-2-1), SMPTE EG 432-1 (P3-D65 / Display P3) and ITU-R BT.2020-2,
all D65 (0.3127, 0.3290), so no chromatic adaptation is involved between them.
"""

import argparse
import pathlib

LUT_SIZE = 1024
MIN_EV = -12.47393
MAX_EV = 4.026069


def agx_sigmoid(x: float) -> float:
    """The AgX default-contrast sigmoid, polynomial fit (Wrensch 2023), input/output in [0, 1]."""
    x2 = x * x
    x4 = x2 * x2
    return (15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2
            + 0.1191 * x - 0.00232)


def write_spi1d(path: pathlib.Path) -> None:
    lines = ["Version 1", "From 0.0 1.0", f"Length {LUT_SIZE}", "Components 1", "{"]
    for i in range(LUT_SIZE):
        lines.append(f"  {agx_sigmoid(i / (LUT_SIZE - 1)):.8f}")
    lines.append("}")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="ascii")


def npm(primaries, white):
    """RGB -> XYZ normalised primary matrix (SMPTE RP 177)."""
    def xyz(xy):
        x, y = xy
        return [x / y, 1.0, (1.0 - x - y) / y]
    cols = [xyz(p) for p in primaries]
    m = [[cols[c][r] for c in range(3)] for r in range(3)]
    s = mul_vec(inverse(m), xyz(white))
    return [[m[r][c] * s[c] for c in range(3)] for r in range(3)]


def inverse(m):
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [[(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
            [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
            [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det]]


def mul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(3)) for c in range(3)] for r in range(3)]


def mul_vec(m, v):
    return [sum(m[r][k] * v[k] for k in range(3)) for r in range(3)]


def ocio_matrix(m):
    """A 3x3 matrix as OCIO's 4x4 row-major list."""
    rows = [m[r] + [0.0] for r in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
    return "[" + ", ".join(f"{0.0 if abs(v) < 1e-12 else v:.10g}" for row in rows for v in row) + "]"


def print_matrices() -> None:
    d65 = (0.3127, 0.3290)
    rec709 = npm([(0.64, 0.33), (0.30, 0.60), (0.15, 0.06)], d65)
    p3d65 = npm([(0.680, 0.320), (0.265, 0.690), (0.150, 0.060)], d65)
    rec2020 = npm([(0.708, 0.292), (0.170, 0.797), (0.131, 0.046)], d65)
    print("Rec.709 -> XYZ   ", ocio_matrix(rec709))
    print("XYZ -> P3-D65    ", ocio_matrix(inverse(p3d65)))
    print("Rec.709 -> P3-D65", ocio_matrix(mul(inverse(p3d65), rec709)))
    print("P3-D65 -> Rec.709", ocio_matrix(mul(inverse(rec709), p3d65)))
    print("Rec.709 -> 2020  ", ocio_matrix(mul(inverse(rec2020), rec709)))
    print("2020 -> Rec.709  ", ocio_matrix(mul(inverse(rec709), rec2020)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--matrices", action="store_true", help="print the config's matrices")
    parser.add_argument("--out", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parent.parent
                        / "resources/ocio/luts/agx_base_sigmoid.spi1d")
    args = parser.parse_args()
    if args.matrices:
        print_matrices()
        return
    write_spi1d(args.out)
    print(f"wrote {args.out} ({LUT_SIZE} entries)")


if __name__ == "__main__":
    main()
