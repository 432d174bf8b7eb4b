"""The old name of images.rgb, kept only while report/viewer.py imports it (the viewer's rewrite to
load a result set's images in the browser removes that import, and this file with it)."""
from images import rgb  # noqa: F401
