from wheelstep_cli.cli import main

main()
