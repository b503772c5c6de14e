#!/usr/bin/env python3
"""Wrap-difference ratios for the corpus (the "measured" column of ORIGIN.md).

For each image, on its luma (0.299 R + 0.587 G + 0.114 B; grey images as they are; alpha ignored),
with values scaled to 0..1 whatever the bit depth:

  col ratio = mean over rows of |v(0,y) - v(W-1,y)|  /  mean over rows and i of |v(i,y) - v(i+1,y)|
  row ratio = mean over cols of |v(x,0) - v(x,H-1)|  /  mean over cols and j of |v(x,j) - v(x,j+1)|

A map that tiles has a wrap difference like any other step inside it: a ratio near 1 (noise puts
it anywhere from about 0.5 to 1.5).  A map that does not tile jumps at the wrap: typically 2 and up.

Reads with PIL when it is installed, else through ImageMagick (`convert FILE -depth 16 pgm:-`).
Usage: measure.py [FILE...]   (no arguments: every image in this folder)
"""
import os
import subprocess
import sys

EXTS = (".png", ".jpg", ".jpeg", ".tga", ".bmp", ".tif", ".tiff", ".exr", ".pgm", ".ppm")


def load_pil(path):
    from PIL import Image
    im = Image.open(path)
    im.load()
    mode = im.mode
    w, h = im.size
    if mode in ("I;16", "I;16B", "I;16L", "I"):
        scale = 65535.0 if mode.startswith("I;16") else float(max(1, max(im.getdata())))
        data = [v / scale for v in im.getdata()]
        return w, h, data, mode
    if mode == "F":
        data = list(im.getdata())
        hi = max(data) or 1.0
        return w, h, [v / hi for v in data], mode
    if mode in ("P", "PA", "LA", "RGBA", "CMYK", "YCbCr", "1", "L;16"):
        im = im.convert("RGBA" if mode in ("P", "PA", "RGBA") else "RGB" if mode != "LA" else "LA")
    if im.mode in ("L", "LA"):
        data = [(p if isinstance(p, int) else p[0]) / 255.0 for p in im.getdata()]
    else:
        data = [(0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]) / 255.0 for p in im.getdata()]
    return w, h, data, mode


def load_magick(path):
    out = subprocess.run(["convert", path + "[0]", "-colorspace", "Gray", "-depth", "16", "pgm:-"],
                         check=True, capture_output=True).stdout
    # binary PGM: P5\n W H\n MAX\n data
    fields, pos = [], 0
    while len(fields) < 4:
        while out[pos:pos + 1].isspace():
            pos += 1
        if out[pos:pos + 1] == b"#":
            pos = out.index(b"\n", pos) + 1
            continue
        end = pos
        while not out[end:end + 1].isspace():
            end += 1
        fields.append(out[pos:end])
        pos = end
    pos += 1
    w, h, mx = int(fields[1]), int(fields[2]), int(fields[3])
    raw = out[pos:]
    if mx > 255:
        data = [(raw[2 * i] << 8 | raw[2 * i + 1]) / mx for i in range(w * h)]
    else:
        data = [raw[i] / mx for i in range(w * h)]
    return w, h, data, "magick-gray"


def load(path):
    try:
        return load_pil(path)
    except Exception:  # no PIL, or a format it cannot read (EXR)
        return load_magick(path)


def ratios(w, h, v):
    wrap_c = sum(abs(v[y * w] - v[y * w + w - 1]) for y in range(h)) / h
    in_c = sum(abs(v[y * w + x] - v[y * w + x + 1]) for y in range(h) for x in range(w - 1)) / (h * (w - 1))
    wrap_r = sum(abs(v[x] - v[(h - 1) * w + x]) for x in range(w)) / w
    in_r = sum(abs(v[y * w + x] - v[(y + 1) * w + x]) for y in range(h - 1) for x in range(w)) / ((h - 1) * w)
    rc = wrap_c / in_c if in_c else float("inf") if wrap_c else 1.0
    rr = wrap_r / in_r if in_r else float("inf") if wrap_r else 1.0
    return rc, rr


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    files = argv or sorted(os.path.join(here, f) for f in os.listdir(here) if f.lower().endswith(EXTS))
    print("| file | size | read as | col ratio | row ratio |")
    print("| --- | --- | --- | --- | --- |")
    for f in files:
        w, h, v, mode = load(f)
        rc, rr = ratios(w, h, v)
        print(f"| {os.path.basename(f)} | {w}x{h} | {mode} | {rc:.2f} | {rr:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
