"""``python -m wheelstep_cli`` and the ``wheelstep`` console script.

The CLI is imported inside :func:`main`, so that Ctrl-C while its libraries load (numpy,
shapely, manifold3d: about half a second) ends in one line, not a traceback.
"""

import gc
import sys


def main() -> None:
    """Run the CLI; exit 130 with one line when interrupted while it loads."""
    try:
        from wheelstep_cli.cli import main as run_cli
    except KeyboardInterrupt:                 # nothing started, nothing written
        print("wheelstep: aborted", file=sys.stderr)
        sys.exit(130)
    # what the imports made lives as long as the process: the collector need not walk it again
    gc.freeze()
    run_cli()


# guarded: spawned worker processes (wheelstep batch --jobs N) import this module again
if __name__ == "__main__":
    main()
