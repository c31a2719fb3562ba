from wheelstep_cli.cli import main

# guarded: spawned worker processes (wheelstep batch --jobs N) import this module again
if __name__ == "__main__":
    main()
