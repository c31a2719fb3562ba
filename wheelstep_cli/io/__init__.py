"""File writers and readers; every write is atomic."""
