import sys

try:
    from wheelstep_cli.cli import main
except KeyboardInterrupt:                     # Ctrl-C while the libraries load: nothing started
    print("wheelstep: interrupted", file=sys.stderr)
    sys.exit(130)

# guarded: spawned worker processes (wheelstep batch --jobs N) import this module again
if __name__ == "__main__":
    main()
