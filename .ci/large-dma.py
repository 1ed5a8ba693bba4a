#!/usr/bin/env python3
"""Writes a large synthetic DMA CSV for the reader's timing (BENCHMARKS.md,
"Reading large files (issue 36, first step)"): ISOTHERMS isotherms from
-40 °C in 2.5 K steps, POINTS frequencies each over 0.1 ... 100 Hz, E* of the
hn-rubber truth (Havriliak-Negami, data/README.md) under its WLF shift.
Usage: .ci/large-dma.py OUT.csv POINTS [ISOTHERMS=60]
(POINTS = 3000: 8.3 MB; 15000: 41.6 MB)."""
import math
import sys


def modulus(omega):
    e0, e1, tau, alpha, beta = 2e6, 2e9, 1e-3, 0.55, 0.4
    return e1 + (e0 - e1) / (1 + (1j * omega * tau) ** alpha) ** beta


def main():
    out, points = sys.argv[1], int(sys.argv[2])
    isotherms = int(sys.argv[3]) if len(sys.argv) > 3 else 60
    with open(out, "w") as f:
        f.write("f,E_storage,E_loss,T\n")
        for k in range(isotherms):
            t = -40 + 2.5 * k
            shift = 10 ** (-8.86 * (t - 20) / (101.6 + t - 20))
            for i in range(points):
                hz = 0.1 * 10 ** (3 * i / (points - 1))
                e = modulus(2 * math.pi * hz * shift)
                f.write(f"{hz:.6e},{e.real:.6e},{e.imag:.6e},{t:.3f}\n")


if __name__ == "__main__":
    main()
