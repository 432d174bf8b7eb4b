"""Reading a result set's images (the runner's linear EXRs, and any other format OpenImageIO reads)
into numpy arrays, through OpenImageIO's Python bindings (Debian's python3-openimageio, which
setup.sh installs): for telling identical images apart whatever their headers' dates, and for
checking that a set's images can be read before a report points at them."""
import numpy as np
import OpenImageIO as oiio


class ImageError(Exception):
    """An image that cannot be read, with OpenImageIO's reason."""


def _open(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        raise ImageError("%s: %s" % (path, oiio.geterror() or "cannot open"))
    return image


def check(path):
    """Raises ImageError unless `path` is an image OpenImageIO can open (its header alone is read)."""
    _open(path).close()


def rgb(path):
    """The first three channels (a grey image's one, repeated) as float32, shape (height, width, 3)."""
    image = _open(path)
    try:
        spec = image.spec()
        pixels = image.read_image(0, 0, 0, min(spec.nchannels, 3), "float")
        if pixels is None:
            raise ImageError("%s: %s" % (path, image.geterror() or "cannot read its pixels"))
    finally:
        image.close()
    pixels = np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, -1)
    return np.repeat(pixels, 3, axis=2) if pixels.shape[2] == 1 else np.ascontiguousarray(pixels[:, :, :3])
