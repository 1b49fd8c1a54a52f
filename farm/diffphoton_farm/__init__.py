"""Final renders across machines: shards of a render's passes on a Dask cluster, merged by
`diffphoton merge` into the image one `diffphoton render` writes, bit for bit (docs/farm.md)."""

from .errors import FarmError
from .runner import plan_shards, render

__all__ = ["FarmError", "plan_shards", "render"]
