#!/usr/bin/env python3
"""Generate Rouge's SYNTHETIC cosmetic measurements (and their true K, S).

No public Kubelka-Munk K and S spectra of real cosmetics exist, so this script
builds products from the representative pigment library in pigments.py
(Duncan two-constant mixing), computes what an instrument would read, adds
seeded measurement noise and writes:

* data/measurements/<slug>.csv          Rouge CSV: r_inf, r (thin layer of
                                        thickness D over the background), rg
* data/measurements/truth/<slug>.csv    the true S and K (mm^-1) on the same grid
* data/measurements/formats/*           one product (Foundation 02 Ivory) in
                                        instrument layouts: X-Rite CGATS,
                                        i1Profiler CGATS (380-730 nm), ArgyllCMS
                                        .ti3 and .sp, Konica Minolta CS-2000
                                        radiance CSV (1 nm)
* data/measurements/bad/*               deliberately malformed files
* data/pigments/pigment_library.csv     the pigment library on 380..780/5 nm

Everything is deterministic: re-running reproduces identical bytes (no dates,
fixed seeds, numpy's PCG64 generator).  Every file says it is synthetic.

Kubelka-Munk (a = 1 + K/S, b = sqrt(a^2 - 1)):
    R_inf = a - b
    R     = (1 - Rg (a - b coth(b S D))) / (a - Rg + b coth(b S D))

Usage: .venv/bin/python python/gen_samples.py [--swatches /tmp/rouge_swatches.png]
"""

from __future__ import annotations

import argparse
import struct
import sys
import zlib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from gen_samples_formats import (  # noqa: E402
    write_bad_files, write_cs2000, write_i1profiler_cgats, write_sp, write_ti3, write_xrite_cgats,
)
from samples_core import (  # noqa: E402
    FINE, FORMAT_SLUG, PRODUCTS, SEED_BASE, Sample, srgb_hex_lab, synthesise, write_pigment_library, write_rouge_csv,
    write_truth,
)


# --------------------------------------------------------------------------
# Swatch sheet (tiny PNG writer, numpy + zlib only)
# --------------------------------------------------------------------------

def write_png(path: Path, img: np.ndarray) -> None:
    h, w, _ = img.shape
    raw = b"".join(b"\x00" + img[y].astype(np.uint8).tobytes() for y in range(h))

    def chunk(tag: bytes, data: bytes) -> bytes:
        return (struct.pack(">I", len(data)) + tag + data
                + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n"
           + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    path.write_bytes(png)


def swatch_sheet(samples: list[Sample], path: Path) -> None:
    """Row per product: R_inf | R over its background | background."""
    cell, gap = 60, 6
    h = len(samples) * (cell + gap) + gap
    w = 3 * (cell + gap) + gap
    img = np.full((h, w, 3), 128, dtype=np.uint8)
    for row, smp in enumerate(samples):
        for col, spec in enumerate((smp.r_inf, smp.r, smp.rg)):
            _, _, rgb = srgb_hex_lab(FINE, spec)
            y0 = gap + row * (cell + gap)
            x0 = gap + col * (cell + gap)
            img[y0:y0 + cell, x0:x0 + cell] = np.round(rgb * 255)
    write_png(path, img)


# --------------------------------------------------------------------------

def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swatches", type=Path, help="also write a PNG swatch sheet here")
    args = ap.parse_args()

    samples = [synthesise(p, SEED_BASE + i) for i, p in enumerate(PRODUCTS, start=1)]
    written = [write_pigment_library()]
    print(f"{'slug':26s} {'R_inf sRGB':10s} {'L*':>5s} {'a*':>6s} {'b*':>6s} "
          f"{'D/mm':>6s} {'bg':5s} grid  min-true-gap  noise-reduced-at")
    for smp in samples:
        p = smp.product
        written.append(write_rouge_csv(smp))
        written.append(write_truth(smp))
        code, lab, _ = srgb_hex_lab(FINE, smp.r_inf)
        red = ",".join(map(str, smp.reduced)) if smp.reduced else "-"
        grid = f"{p.step_nm}nm" + ("%" if p.percent else "")
        print(f"{p.slug:26s} {code:10s} {lab[0]:5.1f} {lab[1]:6.1f} {lab[2]:6.1f} "
              f"{p.thickness_mm:6.3f} {p.background:5s} {grid:5s} "
              f"{smp.true_gap:.4f}@{smp.true_gap_nm:.0f}  {red}")
    fmt = next(s for s in samples if s.product.slug == FORMAT_SLUG)
    written.append(write_xrite_cgats(fmt))
    written.append(write_i1profiler_cgats(fmt))
    written.append(write_ti3(fmt))
    written += write_sp(fmt)
    written.append(write_cs2000(fmt))
    written += write_bad_files(fmt)
    if args.swatches:
        swatch_sheet(samples, args.swatches)
        print(f"swatch sheet: {args.swatches}")
    print(f"wrote {len(written)} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
