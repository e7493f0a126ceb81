#!/usr/bin/env python3
"""The README's rviz picture from a screen grab of scripts/screenshot.sh: checks that every layer
is drawn (its colour on enough pixels of the 3-D view), crops rviz's tool and status bars, adds a
legend under it naming each layer beside its colour, and writes a 256-colour PNG. Exit 1 naming a layer that
is missing (rviz drew nothing of it: a display, a node or its tf failed).

  screenshot_image.py SCREEN.png OUT.png [--crop X Y W H]
"""
import argparse
import os
import sys

import matplotlib
from PIL import Image, ImageDraw, ImageFont

# One hue per layer (src/ros/marker_helpers.h, config/is_graphs.rviz, urdf/): name, RGB for the
# legend, the hue ranges [deg] and the least saturation and value a pixel of it has, and the
# fewest pixels (of the 3-D view, 1248 x 708) that show the layer is drawn. The robot is small:
# a few dozen pixels of its yellow body or its red pose arrow.
LAYERS = [
    ("A-Graph (BIM): surfaces, walls, rooms, doorways", (64, 128, 255), [(195, 235)], 0.5, 0.5,
     2000),
    ("S-Graph (robot): planes, keyframes, rooms, floor", (255, 115, 13), [(15, 36)], 0.7, 0.6,
     1500),
    ("match: paired rooms and walls", (38, 242, 64), [(110, 140)], 0.6, 0.5, 150),
    ("iS-Graph: the S-Graph merged into the BIM", (242, 51, 217), [(295, 320)], 0.6, 0.5, 1500),
    ("robot (yellow) and its pose in the BIM (red)", (242, 191, 26), [(0, 8), (40, 56)], 0.6,
     0.45, 30),
    ("map cloud (white); BIM cloud (pale blue)", (235, 235, 235), [], 0, 0, 0),
]


def count(hsv, hues, min_s, min_v):
    """Pixels of `hsv` (PIL's HSV: each channel 0-255) within a hue range and above s, v."""
    ranges = [(lo * 255 / 360, hi * 255 / 360) for lo, hi in hues]
    return sum(1 for h, s, v in hsv if s >= min_s * 255 and v >= min_v * 255
               and any(lo <= h <= hi for lo, hi in ranges))


def with_legend(view):
    """The view above a band that names each layer beside a swatch of its colour (two columns)."""
    font = ImageFont.truetype(
        os.path.join(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf"), 17)
    line, rows = 26, (len(LAYERS) + 1) // 2
    image = Image.new("RGB", (view.width, view.height + rows * line + 14), (30, 30, 30))
    image.paste(view, (0, 0))
    draw = ImageDraw.Draw(image)
    for i, (name, rgb, *_) in enumerate(LAYERS):
        x, y = 16 + (i // rows) * view.width // 2, view.height + 8 + (i % rows) * line
        draw.rectangle([x, y + 4, x + 28, y + 16], fill=rgb)
        if name.startswith("robot"):  # the pose's red beside the robot's yellow
            draw.rectangle([x + 15, y + 4, x + 28, y + 16], fill=(255, 25, 0))
        draw.text((x + 38, y), name, font=font, fill=(235, 235, 235))
    return image


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("screen")
    parser.add_argument("out")
    parser.add_argument("--crop", type=int, nargs=4, default=(16, 62, 1248, 708),
                        metavar=("X", "Y", "W", "H"), help="the 3-D view in the grab")
    args = parser.parse_args()
    x, y, w, h = args.crop
    view = Image.open(args.screen).convert("RGB").crop((x, y, x + w, y + h))
    hsv = view.convert("HSV")
    hsv = list(hsv.get_flattened_data() if hasattr(hsv, "get_flattened_data") else hsv.getdata())
    missing = []
    for name, _, hues, min_s, min_v, least in LAYERS:
        if not hues:
            continue
        n = count(hsv, hues, min_s, min_v)
        print(f"screenshot: {n:6d} px {name}")
        if n < least:
            missing.append(f"{name} ({n} px < {least})")
    if missing:
        sys.exit("screenshot: error: not drawn: " + "; ".join(missing) + f" ({args.screen})")
    image = with_legend(view)
    image.quantize(256, method=Image.Quantize.FASTOCTREE).save(args.out, optimize=True)


if __name__ == "__main__":
    main()
