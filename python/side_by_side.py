"""The figure the export checks share (python/blender_check.py, python/web_check.py): Rouge's
frame, another renderer's, and the CIEDE2000 map between them side by side, the statistics
below, written with the statistics as JSON beside it."""

import json
import pathlib


def heat(de, mask, top=10.0):
    """ΔE as colour: blue 0, green top/2, red `top` or more; black outside `mask`."""
    import numpy as np
    from PIL import Image

    t = np.clip(de / top, 0, 1)
    rgb = np.stack([t, 1 - np.abs(2 * t - 1), 1 - t], axis=-1) * mask[..., None]
    return Image.fromarray((rgb * 255 + 0.5).astype(np.uint8))


def write_sheet(panels, stats, out):
    """`panels`: (label, PIL image) of one size; `stats`: delta_e_mean, _median, _p95, pixels.
    Writes `out` (PNG) and `out` with .json."""
    from PIL import Image, ImageDraw

    w, h = panels[0][1].size
    sheet = Image.new("RGB", (len(panels) * (w + 8) + 8, h + 52), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (label, img) in enumerate(panels):
        sheet.paste(img, (8 + i * (w + 8), 24))
        draw.text((8 + i * (w + 8), 6), label, fill="black")
    draw.text((8, h + 30), f"dE2000 over the head: mean {stats['delta_e_mean']:.2f}, median "
              f"{stats['delta_e_median']:.2f}, p95 {stats['delta_e_p95']:.2f} ({stats['pixels']} px)", fill="black")
    sheet.save(out)
    pathlib.Path(out).with_suffix(".json").write_text(json.dumps(stats, indent=1) + "\n")
