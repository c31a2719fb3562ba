"""Pure numpy math of the mover: shoe, stairs, linkages, trajectories. No files, no CLI."""
