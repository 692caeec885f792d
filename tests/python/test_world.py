"""The module's World against the command line and against closed forms.

Run by ctest as Python.World (tests/python/CMakeLists.txt).
"""
import _thread
import math
import os
import tempfile
import threading
import time
import unittest

import numpy as np

import softbody
from support import simulate


class SameHashAsTheCommandLine(unittest.TestCase):
    """The same scene and ticks give `softbody simulate`'s state_hash, at one and two threads."""

    def check(self, scene, ticks, sets=()):
        for threads in (1, 2):
            with self.subTest(scene=scene, threads=threads):
                summary, stderr, code = simulate(scene, ticks, threads, sets)
                self.assertEqual(code, 0, stderr)
                world = softbody.World(scene, threads=threads, **dict(sets))
                world.step(ticks)
                self.assertEqual(world.ticks, ticks)
                self.assertEqual(world.threads, summary["threads"])
                self.assertEqual(world.state_hash, summary["state_hash"])
                self.assertEqual(world.status, summary["status"])
                self.assertAlmostEqual(world.energy["total"], summary["energy"]["total"], delta=1e-9)

    def test_pile(self):
        self.check("pile:12", 150)

    def test_soft_cloud(self):
        self.check("cloud:300", 30)

    def test_spring_with_keys(self):
        self.check("spring.json", 200, [("bob.mass", "0.25"), ("spring.stiffness", "20")])

    def test_pyramid(self):
        self.check("pyramid:3", 60)

    def test_stepping_in_pieces_is_stepping_at_once(self):
        a = softbody.World("pile:12")
        b = softbody.World("pile:12")
        a.step(100)
        for _ in range(10):
            b.step(10)
        self.assertEqual(a.state_hash, b.state_hash)

    def test_default_threads_are_the_command_line_s(self):
        summary, _, _ = simulate("pile:2", 1)
        self.assertEqual(softbody.World("pile:2").threads, summary["threads"])
        self.assertEqual(softbody.DEFAULT_THREADS, summary["threads"])


class Views(unittest.TestCase):
    def test_positions_follow_the_world(self):
        world = softbody.World("cloud:50")
        x, y, z = world.positions(0)
        self.assertEqual(x.dtype, np.float32)
        self.assertEqual(z.shape, (50,))
        before = z.copy()
        world.step(10)
        self.assertFalse(np.array_equal(before, z), "the view did not change as the world stepped")
        self.assertTrue(np.all(z < before), "a cloud let go in the air falls")
        fresh = world.positions("body" if "body" in world.soft_bodies else 0)
        self.assertTrue(np.shares_memory(fresh.z, z))
        v = world.velocities(0)
        self.assertTrue(np.all(v.z < 0.0))

    def test_views_are_read_only(self):
        world = softbody.World("cloud:10")
        with self.assertRaises(ValueError):
            world.positions(0).x[0] = 1.0

    def test_an_n_by_3_copy(self):
        world = softbody.World("cloud:10")
        points = np.stack(world.positions(0), axis=1)
        self.assertEqual(points.shape, (10, 3))

    def test_a_viewed_body_is_not_destroyed_under_its_views(self):
        world = softbody.World("cloud:10")
        name = world.soft_bodies[0]
        tail = world.positions(name).x[2:]  # a slice of a view holds the body's memory too
        with self.assertRaisesRegex(RuntimeError, "numpy views"):
            world.destroy(name)
        self.assertEqual(tail.shape, (8,))
        del tail
        world.destroy(name)
        self.assertEqual(world.soft_bodies, [])

    def test_views_survive_what_keeps_the_memory(self):
        """Steps, keys, a reset with nothing to rebuild, a restore, another body made and unmade:
        the views still point at the body's arrays; a reset that rebuilds it is refused."""
        world = softbody.World("cloud:30")
        x = world.positions(0).x
        snapshot = world.snapshot()
        world.step(5)
        world.update(stiffness=50, damping=1, particle_mass=2)
        world.reset()
        world.restore(snapshot)
        world.add_soft_body("other", "cloud:10", position=(3, 0, 1))
        world.step(2)
        world.destroy("other")
        self.assertTrue(np.shares_memory(x, world.positions(0).x))
        world.set("max_particles", 5)
        with self.assertRaisesRegex(RuntimeError, "numpy views"):
            world.reset()
        del x
        world.reset()
        self.assertLessEqual(len(world.positions(0).x), 5)  # rebuilt on at most 5 particles

    def test_views_keep_the_world_alive(self):
        z = softbody.World("cloud:10").positions(0).z
        self.assertEqual(float(np.sum(np.isfinite(z))), 10.0)


class ClosedForms(unittest.TestCase):
    def test_spring_period(self):
        """T = 2 pi sqrt(m / k): the bob's period from its upward crossings of the mean height, 0.5%."""
        for mass, k in ((1.0, 40.0), (0.25, 40.0), (1.0, 10.0)):
            with self.subTest(mass=mass, k=k):
                world = softbody.World("spring.json", sleeping=False, ground=False, **{"bob.mass": mass, "spring.stiffness": k})
                world.step(600)
                series = world.series()
                t, z = series["time"], series["bob z"]
                z = z - z.mean()
                up = np.nonzero((z[:-1] < 0) & (z[1:] >= 0))[0]
                crossings = t[up] - z[up] * (t[up + 1] - t[up]) / (z[up + 1] - z[up])
                period = np.mean(np.diff(crossings))
                expected = 2 * math.pi * math.sqrt(mass / k)
                self.assertAlmostEqual(period / expected, 1.0, delta=0.005)

    def test_time_is_ticks_times_dt(self):
        world = softbody.World("spring.json", dt=0.01)
        world.step(250)
        self.assertEqual(world.ticks, 250)
        self.assertEqual(world.time, 2.5)  # the decimal softbody simulate's sim_time is
        self.assertEqual(world.get("dt"), 0.01)  # a float key read back as written

    def test_the_ledger_adds_up(self):
        """kinetic + gravity + elastic + dissipated stays what the world started with (0.1% of the energy in play)."""
        world = softbody.World("spring.json", **{"spring.damping": 0.5})
        start = world.energy["total"]
        world.step(300)
        e = world.energy
        self.assertGreater(e["dissipated"], 0.1)
        self.assertAlmostEqual(e["total"] + e["dissipated"], start, delta=1e-3 * abs(start))


class Api(unittest.TestCase):
    def test_keys_list_units_and_ranges(self):
        keys = {k["name"]: k for k in softbody.World("spring.json").keys()}
        self.assertEqual(keys["dt"]["unit"], "s")
        self.assertEqual(keys["bob.mass"]["unit"], "kg")
        self.assertEqual(keys["bob.mass"]["value"], 1.0)
        self.assertEqual(keys["spring.stiffness"]["value"], 40.0)
        self.assertIn("N/m", keys["spring.stiffness"]["range"])
        self.assertTrue(keys["bob.mass"]["on_reset"])
        table = {(k["owner"], k["name"]) for k in softbody.key_table()}
        self.assertIn(("world", "dt"), table)

    def test_set_and_reset(self):
        world = softbody.World("spring.json")
        world.set("bob.mass", 0.25)
        world.update(dt=0.01, integrator="rk4")
        self.assertEqual(world.get("bob.mass"), 0.25)
        self.assertEqual(world.get("integrator"), "rk4")
        world.step(5)
        world.reset()
        self.assertEqual(world.ticks, 0)
        self.assertEqual(world.rigid_body("bob")["mass"], 0.25)

    def test_snapshot_and_restore_replay_the_same_bits(self):
        world = softbody.World("pile:12")
        world.step(20)
        moment = world.snapshot()
        world.step(40)
        later = world.state_hash
        world.restore(moment)
        self.assertEqual(world.ticks, 20)
        world.step(40)
        self.assertEqual(world.state_hash, later)
        with self.assertRaisesRegex(ValueError, "another world"):
            softbody.World("pile:12").restore(moment)

    def test_bodies_and_springs_made_and_unmade(self):
        world = softbody.World("spring.json")
        world.add_rigid_body("crate", "box", size=(0.2, 0.2, 0.2), position=(1, 0, 0.5), mass=2)
        world.add_spring({"body": "crate", "point": (0, 0, 0)}, (1, 0, 2), stiffness=50, name="rope")
        world.add_soft_body("jelly", "cloud:20", position=(-1, 0, 1))
        self.assertEqual(world.rigid_bodies, ["bob", "crate"])
        self.assertEqual(world.springs, ["spring", "rope"])
        self.assertEqual(world.positions("jelly").x.shape, (20,))
        world.step(10)
        crate = world.rigid_body("crate")
        self.assertEqual(crate["mass"], 2.0)
        self.assertEqual(crate["position"].shape, (3,))
        world.destroy("crate")  # its spring goes with it
        self.assertEqual(world.springs, ["spring"])
        world.destroy("jelly")
        world.step(1)

    def test_series_columns(self):
        world = softbody.World("spring.json", series_every=2)
        world.step(10)
        series = world.series()
        self.assertEqual(list(series["tick"]), [0, 2, 4, 6, 8, 10])
        for name in ("time", "kinetic", "gravitational", "elastic", "dissipated", "total", "bob z", "spring force"):
            self.assertIn(name, series)
            self.assertEqual(series[name].shape, (6,))
        self.assertEqual(world.series_units()["spring force"], "N")
        world.restart_series()
        self.assertEqual(len(world.series()["time"]), 1)

    def test_render(self):
        world = softbody.World("pile:12")
        world.step(10)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "frame.png")
            try:
                image = world.render(path, size=(80, 60))
            except RuntimeError as error:
                if "OSMesa" in str(error) or "no renderer" in str(error):
                    self.skipTest(str(error))
                raise
            self.assertEqual(image.shape, (60, 80, 4))
            self.assertGreater(image[..., :3].std(), 1.0, "a blank picture")
            with open(path, "rb") as png:
                self.assertEqual(png.read(8), b"\x89PNG\r\n\x1a\n")

    def test_ctrl_c_stops_a_long_step(self):
        world = softbody.World("pile:300", threads=1)
        timer = threading.Timer(0.3, _thread.interrupt_main)
        timer.start()
        with self.assertRaises(KeyboardInterrupt):
            world.step(1_000_000)
        timer.join()
        self.assertLess(world.ticks, 1_000_000)
        ticks = world.ticks
        world.step(1)
        self.assertEqual(world.ticks, ticks + 1)

    def test_the_gil_is_let_go_while_stepping(self):
        world = softbody.World("pile:300", threads=1)
        done = threading.Event()
        counted = 0

        def run():
            world.step(200)
            done.set()

        worker = threading.Thread(target=run)
        worker.start()
        refused = False
        while not done.is_set():
            counted += 1
            if not refused:
                try:
                    world.state_hash  # noqa: B018
                except RuntimeError as error:
                    refused = "another thread" in str(error)
            time.sleep(0.001)
        worker.join()
        self.assertGreater(counted, 5, "Python did not run while the world stepped")
        self.assertTrue(refused, "the world answered while it stepped in another thread")


if __name__ == "__main__":
    unittest.main()
