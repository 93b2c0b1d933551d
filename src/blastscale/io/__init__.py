"""Files at the edge: result files (JSON, NetCDF and CSV histories, Zarr sweep stores), atomic
writes and output folders, versions and provenance. The only package that writes files."""
