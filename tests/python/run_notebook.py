"""Executes a notebook headless, as a class would run it top to bottom; a cell that fails fails.

    python3 run_notebook.py assets/notebooks/spring_period.ipynb [--timeout 120]

Run by ctest as Python.Notebook.<name> (tests/python/CMakeLists.txt), with PYTHONPATH set to the
built module. The notebook is read, run in a fresh kernel (the "python3" kernel: Debian's
python3 with python3-ipykernel), and never
written back: the repository keeps it without outputs.
"""
import argparse
import os
import sys
import time

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebook")
    parser.add_argument("--timeout", type=int, default=120, help="seconds a cell may take (default 120)")
    args = parser.parse_args()
    notebook = nbformat.read(args.notebook, as_version=4)
    stored_outputs = [cell for cell in notebook.cells if cell.cell_type == "code" and (cell.outputs or cell.execution_count)]
    if stored_outputs:
        print(f"{args.notebook}: {len(stored_outputs)} code cells are stored with outputs; clear them before committing",
              file=sys.stderr)
        return 1
    client = NotebookClient(notebook, timeout=args.timeout, kernel_name="python3",
                            resources={"metadata": {"path": os.path.dirname(os.path.abspath(args.notebook))}})
    start = time.monotonic()
    try:
        client.execute()
    except CellExecutionError as error:
        print(f"{args.notebook}: a cell failed\n{error}", file=sys.stderr)
        return 1
    seconds = time.monotonic() - start
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            if output.get("name") == "stdout":
                print(output["text"], end="")
    print(f"{args.notebook}: every cell ran in {seconds:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
