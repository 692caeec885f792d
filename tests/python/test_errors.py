"""Every mistake the command line reports in one line is a Python exception with that line.

Run by ctest as Python.Errors. Each case runs `softbody simulate` with the same scene and keys
and compares its stderr line (without "softbody: ") with str() of the exception.
"""
import unittest

import softbody
from support import error_line, simulate


class SameLineAsTheCommandLine(unittest.TestCase):
    def check(self, kind, scene, sets=(), ticks=1):
        _, stderr, code = simulate(scene, ticks, sets=sets)
        self.assertNotEqual(code, 0, "the command line took it")
        with self.assertRaises(kind) as caught:
            world = softbody.World(scene, **dict(sets))
            world.step(ticks)
        self.assertEqual(str(caught.exception), error_line(stderr))
        return caught.exception

    def test_a_value_out_of_range(self):
        self.check(ValueError, "spring.json", [("bob.mass", "-1")])

    def test_a_misspelt_key(self):
        self.check(ValueError, "spring.json", [("bob.mas", "1")])

    def test_not_a_number(self):
        self.check(ValueError, "spring.json", [("dt", "nan")])
        self.check(ValueError, "spring.json", [("dt", "abc")])

    def test_a_vector_short_of_a_number(self):
        self.check(ValueError, "spring.json", [("gravity", "1,2")])

    def test_a_generated_scene_too_large(self):
        self.check(ValueError, "pile:1000000000")

    def test_a_missing_file(self):
        error = self.check(FileNotFoundError, "no_such_scene.json")
        self.assertEqual(error.errno, 2)
        self.assertIsInstance(error, OSError)

    def test_a_folder_is_not_a_scene(self):
        self.check(OSError, "/tmp")

    def test_a_diverged_world(self):
        sets = [("integrator", "explicit_euler"), ("auto_substeps", "false"), ("spring.stiffness", "10000000")]
        error = self.check(softbody.Diverged, "spring.json", sets, ticks=100)
        self.assertIsInstance(error, RuntimeError)


class PythonValues(unittest.TestCase):
    """A Python value is the text --set would carry, so it is refused with the same line."""

    def test_numbers_as_python_numbers(self):
        for value, text in ((float("nan"), "nan"), (float("inf"), "inf"), (-1, "-1"), (10**30, str(10**30))):
            with self.subTest(value=value):
                _, stderr, _ = simulate("spring.json", 1, sets=[("bob.mass", text)])
                with self.assertRaises(ValueError) as caught:
                    softbody.World("spring.json", **{"bob.mass": value})
                self.assertEqual(str(caught.exception), error_line(stderr))

    def test_set_after_making(self):
        world = softbody.World("spring.json")
        _, stderr, _ = simulate("spring.json", 1, sets=[("spring.stiffness", "-3")])
        with self.assertRaises(ValueError) as caught:
            world.set("spring.stiffness", -3)
        self.assertEqual(str(caught.exception), error_line(stderr))
        self.assertEqual(world.get("spring.stiffness"), 40.0, "a refused key changed the world")

    def test_a_diverged_world_keeps_saying_so(self):
        world = softbody.World("spring.json", integrator="explicit_euler", auto_substeps=False,
                               **{"spring.stiffness": 1e7})
        with self.assertRaises(softbody.Diverged):
            world.step(100)
        self.assertEqual(world.status, "diverged")
        self.assertTrue(world.divergence)
        with self.assertRaises(softbody.Diverged):
            world.step()

    def test_arguments_out_of_range(self):
        with self.assertRaisesRegex(ValueError, "threads: expected a whole number from 1 to 256"):
            softbody.World("pile:2", threads=0)
        world = softbody.World("pile:2")
        with self.assertRaisesRegex(ValueError, "ticks: expected a whole number from 0 to 1000000000"):
            world.step(-1)
        with self.assertRaisesRegex(ValueError, "no soft body|has no soft body"):
            world.positions(0)
        with self.assertRaisesRegex(ValueError, "no rigid body named 'nobody'"):
            world.rigid_body("nobody")


if __name__ == "__main__":
    unittest.main()
