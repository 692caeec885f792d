"""No input crashes the interpreter: random and hostile scenes, keys and values, from a fixed seed.

Run by ctest as Python.Fuzz. Every call either works or raises one of the exceptions the
module documents (ValueError, OSError, TypeError for a wrong Python type, softbody.Diverged);
anything else, or a crash, fails.
"""
import random
import string
import unittest

import softbody

ALLOWED = (ValueError, OSError, TypeError, softbody.Diverged)
SEED = 20261126
ROUNDS = 400

KEYS = [k["name"] for k in softbody.World("spring.json").keys()] + [
    "stiffness", "damping", "mass", "body.mesh", "nobody.mass", "bob.", ".mass", "", "bob..mass", "spring.rest_length",
    "bob.shape", "bob.orientation", "bob.rotation", "particle_mass", "max_particles", "pinned", "mesh", "scale"]
SCENES = ["spring.json", "cloud:20", "pile:5", "pyramid:2", "sheet:4", "", "pile:0", "pile:5000x", "cloud:",
          "cloud:400001", "pile:-3", "ball:9", "torus:2x2", "random:0", "pile:3+", "+", ":", "/", "/dev/null",
          "/proc/self/mem", "assets/scenes", "\x00", "é.json", "spring.json\x00x"]


def hostile_value(rng):
    choices = [
        float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 5e-324, 0, -0.0, 1, -1, 10**400, -(10**19), 2**63,
        True, False, None, "", "none", "auto", "all", "rk4", "nan", "1e999", "0x10", " 1", "1,2,3", "1,2,3,4",
        ",,,", "-", "\x00", "é" * 5, (1, 2, 3), (float("nan"), 0, 0), [1e308] * 3, [0, 5, 7], [-1], [2**40],
        ((1, 2), 3), [], (1,), b"bytes", object(), {"a": 1}, 3 + 4j,
        "".join(rng.choice(string.printable) for _ in range(rng.randint(0, 12))),
        rng.uniform(-1e6, 1e6), rng.randint(-10**6, 10**6),
    ]
    return rng.choice(choices)


class NothingCrashes(unittest.TestCase):
    def attempt(self, call, *args, **kwargs):
        try:
            return call(*args, **kwargs)
        except ALLOWED:
            return None

    def test_scenes(self):
        rng = random.Random(SEED)
        names = SCENES + ["".join(rng.choice(string.printable) for _ in range(rng.randint(0, 20))) for _ in range(100)]
        for name in names:
            with self.subTest(scene=name):
                world = self.attempt(softbody.World, name)
                if world is not None:
                    self.attempt(world.step, 2)

    def test_keys_and_values(self):
        rng = random.Random(SEED + 1)
        for _ in range(ROUNDS):
            scene = rng.choice(["spring.json", "cloud:12", "pile:3"])
            key = rng.choice(KEYS)
            value = hostile_value(rng)
            with self.subTest(scene=scene, key=key, value=repr(value)[:40]):
                if rng.random() < 0.5:
                    world = self.attempt(softbody.World, scene, **{key: value})
                else:
                    world = softbody.World(scene)
                    self.attempt(world.set, key, value)
                if world is None:
                    continue
                self.attempt(world.step, 3)
                self.attempt(world.reset)
                self.attempt(world.step, 1)
                self.assertEqual(len(world.state_hash), 16)
                world.energy  # noqa: B018
                world.series()

    def test_calls_with_hostile_arguments(self):
        rng = random.Random(SEED + 2)
        world = softbody.World("spring.json")
        calls = [world.step, world.positions, world.velocities, world.rigid_body, world.destroy, world.get,
                 lambda v: world.render(size=v), lambda v: world.add_rigid_body("box" + str(rng.random()), v),
                 lambda v: world.add_soft_body("soft" + str(rng.random()), v),
                 lambda v: world.add_spring(v, (0, 0, 1), stiffness=v), lambda v: setattr(world, "threads", v),
                 lambda v: softbody.World("pile:2", threads=v), lambda v: world.restore(v)]
        for _ in range(ROUNDS):
            call = rng.choice(calls)
            value = hostile_value(rng)
            with self.subTest(value=repr(value)[:40]):
                self.attempt(call, value)
        self.attempt(world.step, 5)


if __name__ == "__main__":
    unittest.main()
