#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Try to falsify the proved lower bound on the contacts a ball needs to come to rest
(`least_contacts_to_rest`, doc/chains.md "How many bounces before rest") on random
balls that do come to rest.

Each case draws an exponent (0.1 to 6), a mass (1e-6 to 1e3 kg), a gravity (0.1 to
1000 m/s^2), the depth at which the ball rests (1e-6 to 1e-2 m, which sets the
stiffness), a damping that gives some 10 to 3000 bounces, a drop, a throw up or down,
the floor on either side, and no wall above, an elastic one or a damped one (within
reach or not). The ball is run until it rests (Adams, rtol 1e-8); then, where the bound
applies (the library refuses at max_events = 1), the bound is bracketed by bisection on
`max_events` (the library refuses when bound > 10.00001 max_events + 2) and

- the bound is broken when it is surely above the real contacts;
- where the bound is above 100 (a bracket within 10 %), the ratio of the real contacts
  to the bracket's top is reported (the ratio to the bound is at least that).

The library is not asked for the bound directly: the refusal is what a user meets.
Usage (a shared build; about 400 s for some 3000 cases on 2 cores):

    HCIMPACT_LIBRARY=build/shared/libhcimpact.so PYTHONPATH=python \\
        python3 test/cvode/rest_bound_sweep.py --seed 1 --seconds 400

Exit status 1 when a ball came to rest in fewer contacts than the bound.
"""

import argparse
import math
import random
import sys
import time

import hcimpact

REFUSAL = "to come to rest"


def draw(rng):
    """A random ball that should come to rest within about 10^4 contacts."""
    n = math.exp(rng.uniform(math.log(0.1), math.log(6.0)))
    mass = 10.0 ** rng.uniform(-6.0, 3.0)
    gravity = 9.81 * 10.0 ** rng.uniform(-2.0, 2.0)
    depth = 10.0 ** rng.uniform(-6.0, -2.0)
    weight = mass * gravity
    stiffness = weight / depth ** n
    rest_energy = weight * depth * n / (n + 1.0)
    rest_speed = math.sqrt(2.0 * rest_energy / mass)
    damping = 1.0 / (10.0 ** rng.uniform(1.0, 3.5) * rest_speed)
    drop = rng.choice([0.0, depth * 10.0 ** rng.uniform(0.0, 3.0)])
    speed = rng.choice([0.0, 1.0, -1.0]) * rest_speed * 10.0 ** rng.uniform(-1.0, 1.0)
    side = rng.choice([-1, 1])
    above = rng.choice([None, "elastic", "damped"])
    floor = dict(stiffness=stiffness, exponent=n, damping=damping, gap=drop)
    roof = None
    if above is not None:
        roof = dict(stiffness=stiffness, exponent=n,
                    damping=damping if above == "damped" else 0.0,
                    gap=drop + depth * rng.uniform(1.0, 100.0))
    kwargs = dict(gravity=side * gravity, rtol=1e-8, integrator="adams", max_steps=10**7)
    if side < 0:
        kwargs.update(wall_left=floor, wall_right=roof)
    else:
        kwargs.update(wall_right=floor, wall_left=roof)
    return [mass], [-side * speed], kwargs


def refused(masses, velocities, kwargs, max_events):
    """Whether the library refuses the run by the bound at this max_events."""
    try:
        hcimpact.chain(masses, velocities, max_events=max_events, **kwargs)
    except hcimpact.HcimpactError as error:
        return REFUSAL in str(error)
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seconds", type=float, default=120.0)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    cases = broken = applied = 0
    ratios = []
    start = time.monotonic()
    while time.monotonic() - start < args.seconds:
        masses, velocities, kwargs = draw(rng)
        try:
            result = hcimpact.chain(masses, velocities, max_events=10**6, **kwargs)
        except hcimpact.HcimpactError:
            continue
        if not result.rested:
            continue
        cases += 1
        # the contact in which it rests has not ended, and is not listed
        contacts = len(result.contacts) + 1
        if not refused(masses, velocities, kwargs, 1):
            continue
        applied += 1
        low, high = 1, 2
        while refused(masses, velocities, kwargs, high):
            low, high = high, 2 * high
        while high - low > 1:
            middle = (low + high) // 2
            if refused(masses, velocities, kwargs, middle):
                low = middle
            else:
                high = middle
        # the bound lies in (10.00001 low + 2, 10.00001 high + 2]
        if 10.00001 * low + 2.0 > contacts:
            broken += 1
            print(f"BROKEN: {contacts} contacts, bound above {10.00001 * low + 2.0}:",
                  masses, velocities, kwargs)
            continue
        if low >= 10:
            # (a bracket within 10 %)
            ratios.append(contacts / (10.00001 * high + 2.0))
    print(f"{cases} balls at rest, {broken} with fewer contacts than the bound; the bound "
          f"applied to {applied}", end="")
    if ratios:
        print(f"; where it is above 100, real contacts over the bound at least "
              f"{min(ratios):.2f} (largest {max(ratios):.2f}, {len(ratios)} balls)")
    else:
        print()
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
