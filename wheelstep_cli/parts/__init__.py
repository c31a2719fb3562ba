"""Part pipelines shared by the CLI and batch: design -> math -> solids -> checked files."""
