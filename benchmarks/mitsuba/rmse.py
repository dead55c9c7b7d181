#!/usr/bin/env python3
"""rmse.py IMAGE.pfm REFERENCE.pfm: the error of IMAGE against REFERENCE,
computed as trac0r's image_error (trac0r/noise.cpp):

- rmse: sqrt(sum over pixels of |image - reference|^2 (R, G, B) / (3 n)),
  in double;
- relative MSE: the mean over pixels of (L - L_ref)^2 / (L_ref^2 + 0.01),
  L the luminance 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709), computed in
  float as kernel::luminance, the rest in double;
- PSNR: -20 log10(rmse), peak 1.

Reads PFM as trac0r's read_pfm: colour ('PF') only, the sign of the scale
gives the byte order, rows stored bottom first. Measurement only; needs
numpy.
"""

import sys

import numpy as np


def read_pfm(path):
    """An (height, width, 3) float32 array, row 0 at the top."""
    with open(path, "rb") as f:
        data = f.read()
    # Header: 'PF', width, height, scale, separated by whitespace, then one
    # whitespace byte (std::istream >> as trac0r reads it).
    fields = []
    pos = 0
    while len(fields) < 4:
        while pos < len(data) and data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while pos < len(data) and not data[pos:pos + 1].isspace():
            pos += 1
        if start == pos:
            raise SystemExit(path + ": not a colour PFM (expected 'PF', size and scale)")
        fields.append(data[start:pos].decode("ascii", "replace"))
    pos += 1
    magic, width, height, scale = fields[0], int(fields[1]), int(fields[2]), float(fields[3])
    if magic != "PF" or width <= 0 or height <= 0 or scale == 0.0:
        raise SystemExit(path + ": not a colour PFM (expected 'PF', size and scale)")
    dtype = "<f4" if scale < 0.0 else ">f4"
    count = width * height * 3
    if len(data) - pos < 4 * count:
        raise SystemExit(path + ": PFM data is truncated")
    pixels = np.frombuffer(data, dtype=dtype, count=count, offset=pos)
    return pixels.reshape(height, width, 3)[::-1].astype(np.float32)


def luminance(img):
    """kernel::luminance, in float: 0.2126f * r + 0.7152f * g + 0.0722f * b."""
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return ((np.float32(0.2126) * r + np.float32(0.7152) * g)
            + np.float32(0.0722) * b).astype(np.float32)


def image_error(image, reference):
    if image.shape != reference.shape:
        raise SystemExit("image is %dx%d, reference is %dx%d"
                         % (image.shape[1], image.shape[0], reference.shape[1],
                            reference.shape[0]))
    n = image.shape[0] * image.shape[1]
    d = image.astype(np.float64) - reference.astype(np.float64)
    rmse = float(np.sqrt(np.sum(d * d) / (3.0 * n)))
    l = luminance(image).astype(np.float64)
    l_ref = luminance(reference).astype(np.float64)
    relative_mse = float(np.sum((l - l_ref) ** 2 / (l_ref * l_ref + 0.01)) / n)
    psnr = -20.0 * np.log10(rmse) if rmse > 0.0 else float("inf")
    return rmse, relative_mse, psnr


def main():
    if len(sys.argv) != 3:
        raise SystemExit("usage: rmse.py IMAGE.pfm REFERENCE.pfm")
    rmse, relative_mse, psnr = image_error(read_pfm(sys.argv[1]), read_pfm(sys.argv[2]))
    print("rmse %.9g" % rmse)
    print("relative_mse %.9g" % relative_mse)
    print("psnr %.6g dB" % psnr)


if __name__ == "__main__":
    main()
