#!/usr/bin/env python3
"""Independent reference for the accumulation point of complete chatter of a
single-degree-of-freedom impact oscillator, in 50-digit arithmetic (mpmath),
written from the model alone (no impactkit code):

    m x'' + c x' + k x = A cos(Ω t)   while x < xs,   v -> -r v at x = xs.

From a release (x = xs, v = 0 where A cos Ωt = k xs, the force falling) the
free flight is the closed form x = X cos(Ωt − φ) + e^{−ζ s}(B cos ω_d s + C
sin ω_d s); each impact is its first root after the last one (bracketed on
a grid of the flight, refined to 50 digits); the bounces are followed until
their speed is below 1e-25, and Budd & Dux's 2 r u / (a (1 − r)) adds the
remaining (< 1e-24) time. Prints, for each Ω given, the accumulation phase,
the release phase and the stuck duration (all mod T), and the number of
impacts.

    sdof_chatter_mp.py m c k A xs r OMEGA...
    sdof_chatter_mp.py m c k A xs r --end LOW HIGH
    sdof_chatter_mp.py m c k A xs r --rounding TRIALS OMEGA

The second form locates the end of the sticking family between LOW (the
chatter after a release accumulates while the stop pushes) and HIGH (it
does not: a bounce does not come back, or the force has turned at an
impact) by bisection to 1e-13.

The third measures the floor that double precision puts on the
accumulation point: each impact time is moved by a random fraction in
[-1/2, 1/2] of its double's ulp (what storing it as a double does), the
state taken there with x = xs, and the accumulation point's shifts over
TRIALS such runs printed with their rms.
"""
import math
import random
import sys

import mpmath as mp

mp.mp.dps = 50


def flight(m, c, k, a_force, omega, t0, x0, v0):
    """x(t), v(t), acc(t) of the free flight from (x0, v0) at t0."""
    wn2 = k / m
    zeta = c / (2 * m)
    wd = mp.sqrt(wn2 - zeta**2)
    denom = mp.sqrt((k - m * omega**2) ** 2 + (c * omega) ** 2)
    amp = a_force / denom
    phi = mp.atan2(c * omega, k - m * omega**2)

    def xp(t):
        return amp * mp.cos(omega * t - phi)

    def vp(t):
        return -amp * omega * mp.sin(omega * t - phi)

    b = x0 - xp(t0)
    cc = (v0 - vp(t0) + zeta * b) / wd

    def x(t):
        s = t - t0
        return xp(t) + mp.exp(-zeta * s) * (b * mp.cos(wd * s) + cc * mp.sin(wd * s))

    def v(t):
        s = t - t0
        e = mp.exp(-zeta * s)
        return vp(t) + e * (
            (-zeta * b + wd * cc) * mp.cos(wd * s) + (-zeta * cc - wd * b) * mp.sin(wd * s)
        )

    return x, v


def next_impact(x, xs, t0, guess_span, period):
    """The first t > t0 with x(t) = xs, crossing upwards."""
    g = lambda t: x(t) - xs
    steps = 400
    h = guess_span / steps
    t = t0 + h * mp.mpf("1e-6")
    prev = g(t)
    for _ in range(steps * 8):
        t_next = t + h
        cur = g(t_next)
        if prev < 0 and cur >= 0:
            return mp.findroot(g, (t, t_next), solver="anderson")
        t, prev = t_next, cur
        if t - t0 > 4 * period:
            break
    return None


def chatter(m, c, k, a_force, xs, r, omega, rounding=None):
    """The accumulation point of the chatter after the release at Ω and its
    number of impacts, or None if it does not accumulate before the next
    release (past the family's end the mass leaves the stop instead).
    `rounding`, a random.Random, moves each impact time within half an ulp
    of its double."""
    period = 2 * mp.pi / omega
    release = mp.acos(k * xs / a_force) / omega
    t, x0, v0 = release, xs, mp.mpf(0)
    impacts = 0
    span = period
    while True:
        x, v = flight(m, c, k, a_force, omega, t, x0, v0)
        te = next_impact(x, xs, t, span, period)
        if te is None or te > release + period:
            return None
        if rounding is not None:
            te += mp.mpf(rounding.uniform(-0.5, 0.5)) * math.ulp(float(te))
        u = v(te)
        impacts += 1
        accel = (a_force * mp.cos(omega * te) - k * xs - c * (-r * u)) / m
        span = 4 * r * u / accel if accel > 0 else period
        t, x0, v0 = te, xs, -r * u
        if u < mp.mpf("1e-25"):
            return te + 2 * r * u / (accel * (1 - r)), impacts


def locate_end(m, c, k, a_force, xs, r, low, high):
    while high - low > mp.mpf("1e-13"):
        mid = (low + high) / 2
        if chatter(m, c, k, a_force, xs, r, mid) is None:
            high = mid
        else:
            low = mid
    print(f"family end between {mp.nstr(low, 16)} and {mp.nstr(high, 16)}")


def rounding_floor(m, c, k, a_force, xs, r, trials, omega):
    exact = chatter(m, c, k, a_force, xs, r, omega)[0]
    shifts = [
        float(chatter(m, c, k, a_force, xs, r, omega, random.Random(seed))[0] - exact)
        for seed in range(trials)
    ]
    rms = math.sqrt(sum(d * d for d in shifts) / trials)
    print(f"accumulation point shifted by {' '.join(f'{d:.2e}' for d in shifts)}; rms {rms:.2e}")


def main():
    m, c, k, a_force, xs, r = (mp.mpf(v) for v in sys.argv[1:7])
    if sys.argv[7] == "--end":
        locate_end(m, c, k, a_force, xs, r, mp.mpf(sys.argv[8]), mp.mpf(sys.argv[9]))
        return
    if sys.argv[7] == "--rounding":
        rounding_floor(m, c, k, a_force, xs, r, int(sys.argv[8]), mp.mpf(sys.argv[9]))
        return
    for omega_text in sys.argv[7:]:
        omega = mp.mpf(omega_text)
        period = 2 * mp.pi / omega
        release = mp.acos(k * xs / a_force) / omega
        found = chatter(m, c, k, a_force, xs, r, omega)
        if found is None:
            print(f"omega {omega_text}: no sticking")
            continue
        accumulation, impacts = found
        next_release = release + period * mp.ceil((accumulation - release) / period)
        stuck = next_release - accumulation
        phase = accumulation - period * mp.floor(accumulation / period)
        print(
            f"omega {omega_text}: accumulation phase {mp.nstr(phase, 20)}, release phase "
            f"{mp.nstr(release, 20)}, stuck duration {mp.nstr(stuck, 20)}, impacts {impacts}"
        )


if __name__ == "__main__":
    main()
