"""Pure numpy math of non-circular gears: pitch curves, sectors, teeth, meshing. No files, no CLI."""
