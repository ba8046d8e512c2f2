# SPDX-License-Identifier: Apache-2.0
"""Determinism: each random case run twice in a row, then again after other cases and
in the reverse order, and in a second process; all results must be bit-identical.
python3 determinism.py FIRST COUNT"""
import hashlib, subprocess, sys
import numpy as np
import hcimpact
from run_random import draw


def digest(case, **kw):
    try:
        r = hcimpact.chain(**case, **kw)
    except hcimpact.HcimpactError as e:
        return "error " + str(e)
    h = hashlib.sha256()
    for a in (r.positions, r.velocities, r.contacts.tobytes(),
              np.array([r.time, r.energy_error, r.dissipated, r.initial_energy, r.rest_time])):
        h.update(np.asarray(a).tobytes() if not isinstance(a, bytes) else a)
    h.update(repr(sorted(r.counters.items())).encode() + r.method_used.encode())
    return h.hexdigest()


def main():
    first, count = int(sys.argv[1]), int(sys.argv[2])
    seeds = [s for s in range(first, first + count) if s not in (75,)]
    variants = [dict(), dict(integrator="adams"), dict(method="integrated")]
    a = {(s, i): digest(draw(s), **v) for s in seeds for i, v in enumerate(variants)}
    b = {(s, i): digest(draw(s), **v) for s in reversed(seeds) for i, v in enumerate(variants)}
    if len(sys.argv) > 3:      # child: print digests
        for k in sorted(a):
            print(k, a[k])
        return
    out = subprocess.run([sys.executable, __file__, str(first), str(count), "child"],
                         capture_output=True, text=True).stdout.split("\n")
    c = {}
    for line in out:
        if line:
            k, d = line.rsplit(" ", 1)
            c[k] = d
    diff = [k for k in a if a[k] != b[k] or c.get(str(k)) != a[k]]
    print(f"runs {len(a)} x 3; differing: {len(diff)} {diff[:10]}")


if __name__ == "__main__":
    main()
