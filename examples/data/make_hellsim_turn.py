#!/usr/bin/python3
"""Writes hellsim_turn_north.txt: a 60 s HellSim navigation export of a helicopter at 40 m/s
turning right through north (heading 315° → 0°/360° → 75°), for examples/hellsim_flight.yaml.

Column layout of SENSOR-SPEC §5 (the HellSim ASCII export), one record a line, with its header:
  Pic # Time-Tag Heading Pitch Roll X-Vel Y-Vel Z-Vel N-Vel E-Vel D-Vel Veloc Latitude Long. Altitude
angles in degrees, velocities in m/s (X/Y/Z body frame: forward, right, down; N/E/D local level),
latitude/longitude in degrees, altitude in metres (WGS-84 ellipsoidal height).

The flight, level at a constant ellipsoidal height:
  0–5 s     straight and level, heading 315°;
  5–8 s     the turn rate ramps linearly from 0 to 3°/s (roll-in);
  8–45 s    a steady right turn at 3°/s (radius ≈ 764 m), crossing north at t = 21.5 s;
  45–48 s   roll-out, the rate ramping back to 0 (heading now 75°);
  48–60 s   straight and level, heading 75°.
Roll is the coordinated bank atan(v·ψ̇/g) (right wing down positive), pitch a constant −2°
(nose down in cruise). The position is integrated on the WGS-84 ellipsoid (meridian and
prime-vertical radii) with 1 ms steps and the heading integrated exactly from its rate, so the
velocity columns, the attitude and the positions agree. 10 records a second, Time-Tag in ticks
of 0.5 ms (the scenario's tick_s) starting at 5529 and wrapping at 65,536 like the real 16-bit
counter (it wraps once, near t = 30 s).

Run with /usr/bin/python3 from anywhere; it needs only the standard library and writes the file
next to itself, or to the path given as its one argument (tests/test_examples.cpp checks that the
bundled file is what this script writes). The output is fully determined by the constants below.
"""
import math
import os
import sys

# WGS-84
A_M = 6378137.0
F = 1.0 / 298.257223563
E2 = F * (2.0 - F)
G_MPS2 = 9.80665

START_LAT_DEG = 48.6812  # about 770 m south and 560 m west of the examples' origin
START_LON_DEG = 10.8371  # (48.6881, 10.8447, 450 m)
HEIGHT_M = 550.0  # about 100 m above the origin's ground
SPEED_MPS = 40.0
PITCH_DEG = -2.0
HEADING_0_DEG = 315.0
TURN_RATE_DEG_S = 3.0
TURN_START_S = 5.0
RAMP_S = 3.0
STEADY_S = 37.0
DURATION_S = 60.0
RECORD_HZ = 10
TICK_S = 0.0005
FIRST_TAG = 5529
TAG_MODULUS = 65536
STEP_S = 0.001
HEADER = ("Pic # Time-Tag Heading Pitch Roll X-Vel Y-Vel Z-Vel N-Vel E-Vel D-Vel Veloc "
          "Latitude Long. Altitude")


def turn_rate_deg_s(t):
    """ψ̇(t): 0, ramp up, steady, ramp down, 0 (piecewise linear, continuous)."""
    t1 = TURN_START_S
    t2 = t1 + RAMP_S
    t3 = t2 + STEADY_S
    t4 = t3 + RAMP_S
    if t <= t1 or t >= t4:
        return 0.0
    if t < t2:
        return TURN_RATE_DEG_S * (t - t1) / RAMP_S
    if t <= t3:
        return TURN_RATE_DEG_S
    return TURN_RATE_DEG_S * (t4 - t) / RAMP_S


def heading_deg(t):
    """ψ(t) = ψ0 + ∫ψ̇ dt, exactly (the integral of a piecewise-linear rate), not wrapped."""
    t1 = TURN_START_S
    t2 = t1 + RAMP_S
    t3 = t2 + STEADY_S
    t4 = t3 + RAMP_S
    w = TURN_RATE_DEG_S
    psi = HEADING_0_DEG
    if t > t1:
        u = min(t, t2) - t1
        psi += 0.5 * w * u * u / RAMP_S
    if t > t2:
        psi += w * (min(t, t3) - t2)
    if t > t3:
        u = min(t, t4) - t3
        psi += w * u - 0.5 * w * u * u / RAMP_S
    return psi


def roll_deg(t):
    return math.degrees(math.atan(SPEED_MPS * math.radians(turn_rate_deg_s(t)) / G_MPS2))


def body_velocity(v_ned, heading, pitch, roll):
    """Rᵀ · v_ned with R = Rz(heading) · Ry(pitch) · Rx(roll) (SENSOR-SPEC §4, eq 5.1–5.5)."""
    def rz(a, v):
        c, s = math.cos(a), math.sin(a)
        return (c * v[0] + s * v[1], -s * v[0] + c * v[1], v[2])  # Rz(a)ᵀ · v

    def ry(a, v):
        c, s = math.cos(a), math.sin(a)
        return (c * v[0] - s * v[2], v[1], s * v[0] + c * v[2])  # Ry(a)ᵀ · v

    def rx(a, v):
        c, s = math.cos(a), math.sin(a)
        return (v[0], c * v[1] + s * v[2], -s * v[1] + c * v[2])  # Rx(a)ᵀ · v

    return rx(math.radians(roll), ry(math.radians(pitch), rz(math.radians(heading), v_ned)))


def radii_m(lat_rad):
    """Meridian radius M and prime-vertical radius N of WGS-84 at a latitude."""
    w = math.sqrt(1.0 - E2 * math.sin(lat_rad) ** 2)
    return A_M * (1.0 - E2) / w ** 3, A_M / w


def records():
    lat = math.radians(START_LAT_DEG)
    lon = math.radians(START_LON_DEG)
    steps_per_record = round(1.0 / (RECORD_HZ * STEP_S))
    count = round(DURATION_S * RECORD_HZ) + 1
    for i in range(count):
        t = i / RECORD_HZ
        yield t, lat, lon
        for j in range(steps_per_record):  # midpoint rule over each 1 ms step
            tm = t + (j + 0.5) * STEP_S
            psi = math.radians(heading_deg(tm))
            m, n = radii_m(lat)
            v = SPEED_MPS  # level: the velocity is horizontal, the nose 2° below it
            lat += v * math.cos(psi) / (m + HEIGHT_M) * STEP_S
            lon += v * math.sin(psi) / ((n + HEIGHT_M) * math.cos(lat)) * STEP_S


def main():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hellsim_turn_north.txt")
    if len(sys.argv) > 1:
        path = sys.argv[1]
    lines = [HEADER]
    for i, (t, lat, lon) in enumerate(records()):
        heading = heading_deg(t)
        roll = roll_deg(t)
        v = SPEED_MPS
        v_ned = (v * math.cos(math.radians(heading)), v * math.sin(math.radians(heading)), 0.0)
        x, y, z = body_velocity(v_ned, heading, PITCH_DEG, roll)
        tag = (FIRST_TAG + round(t / TICK_S)) % TAG_MODULUS
        shown_heading = round(heading % 360.0, 4) % 360.0  # never print 360.0000
        lines.append(
            f"{i + 1} {tag} {shown_heading:.4f} {PITCH_DEG:.5f} {roll:.5f} "
            f"{x:.5f} {y:.5f} {z:.5f} {v_ned[0]:.3f} {v_ned[1]:.3f} {v_ned[2]:.3f} {v:.2f} "
            f"{math.degrees(lat):.8f} {math.degrees(lon):.8f} {HEIGHT_M:.4f}")
    with open(path, "w", encoding="ascii", newline="\n") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
