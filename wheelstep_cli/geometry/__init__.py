"""2D outlines to manifold3d solids to trimesh meshes, and mesh validity checks."""
