"""What the Python benchmarks share with `tradeoff --ensemble` (src/tradeoff/ensemble.h):
the members' shifts, drawn as member_shift draws them, and the quantiles of
the floor, taken as quantile() takes them."""
import math


def member_shifts(k, shift, seed=1):
    """The K members' (dx, dz) in m: evenly spaced around the circle, turned
    together by an angle from splitmix64 of the seed. With gravity along -y
    ensemble.cpp's horizontal axes are u = z, w = x."""
    mask = (1 << 64) - 1
    z = (seed + 0x9E3779B97F4A7C15) & mask
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
    z ^= z >> 31
    turn = (z >> 11) * 2.0 ** -53
    return [(shift * math.sin(2 * math.pi * (m + turn) / k),
             shift * math.cos(2 * math.pi * (m + turn) / k)) for m in range(k)]


def quantile(values, q):
    """The q-quantile by linear interpolation between order statistics."""
    v = sorted(values)
    at = q * (len(v) - 1)
    lo = int(math.floor(at))
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (at - lo) * (v[hi] - v[lo])
