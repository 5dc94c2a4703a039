#!/usr/bin/env python3
"""N synthetic LEO element sets (OMM JSON) for measuring the partitioned tracker: circular-ish orbits,
altitudes 500-1200 km, inclinations 45-99 deg, random planes and phases (seeded). Not real objects."""
import json, math, random, sys
n, seed, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
rng = random.Random(seed)
mu, re = 398600.8, 6378.135
objs = []
for i in range(n):
    alt = rng.uniform(500, 1200)
    a = re + alt
    mm = math.sqrt(mu / a**3) * 86400 / (2 * math.pi)
    objs.append({"OBJECT_NAME": f"SYN {i}", "OBJECT_ID": f"2026-{i // 26:03d}{chr(65 + i % 26)}",
        "EPOCH": "2026-03-20T00:00:00.000000", "MEAN_MOTION": round(mm, 8), "ECCENTRICITY": round(rng.uniform(0.0001, 0.005), 7),
        "INCLINATION": round(rng.choice([rng.uniform(45, 75), rng.uniform(96, 99)]), 4),
        "RA_OF_ASC_NODE": round(rng.uniform(0, 360), 4), "ARG_OF_PERICENTER": round(rng.uniform(0, 360), 4),
        "MEAN_ANOMALY": round(rng.uniform(0, 360), 4), "EPHEMERIS_TYPE": 0, "CLASSIFICATION_TYPE": "U",
        "NORAD_CAT_ID": 70000 + i, "ELEMENT_SET_NO": 999, "REV_AT_EPOCH": 100, "BSTAR": 0.00001,
        "MEAN_MOTION_DOT": 0, "MEAN_MOTION_DDOT": 0})
json.dump(objs, open(out, "w"))
