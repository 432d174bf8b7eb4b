"""A folder written whole or not at all: its files are written into a new folder beside it (on the
same file system) and moved into it once every one is written, so that a failure on the way (a
full disk, an error while drawing) leaves it as it was: absent, or holding the earlier report."""
import contextlib
import errno
import os
import re
import shutil
import tempfile


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _move_in(staging, destination):
    """The entries of `staging` into `destination`, each replacing the entry of its name there (the
    replaced ones are left in `staging`, to be removed with it)."""
    if not os.path.lexists(destination):
        os.rename(staging, destination)
        return
    for name in sorted(os.listdir(staging)):
        target = os.path.join(destination, name)
        if os.path.lexists(target):
            os.rename(target, os.path.join(staging, ".replaced-" + name))
        os.rename(os.path.join(staging, name), target)


def _staging_prefix(name, pid):
    """The staging folder's name before mkdtemp's random tail: the program's temporaries' form
    (.tmp-PID-NAME, common/core/atomic_file.h), so that the owner of one left behind is known."""
    return ".tmp-%d-%s." % (pid, name)


def _owner_is_gone(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:
        return False  # another user's process
    return False


def _remove_stale_staging(parent, name):
    """The staging folders of `name` that a killed report left in `parent`."""
    pattern = re.compile(r"\.tmp-(\d+)-" + re.escape(name) + r"\.[^/]*$")
    with contextlib.suppress(OSError):
        for entry in os.scandir(parent):
            m = pattern.match(entry.name)
            if m and int(m.group(1)) != os.getpid() and entry.is_dir(follow_symlinks=False) and _owner_is_gone(int(m.group(1))):
                shutil.rmtree(entry.path, ignore_errors=True)


@contextlib.contextmanager
def staged(destination):
    """Yields a new empty folder beside `destination`; when the block ends without an exception,
    its entries replace those of the same names in `destination` (made when absent, with the
    permissions a new folder gets; other entries stay). The staging folder is removed either way, and
    one that a killed report left beside `destination` before this one is made.
    OSError (its filename the destination) where `destination` is a file or cannot be written."""
    if os.path.lexists(destination) and not os.path.isdir(destination):
        raise NotADirectoryError(errno.ENOTDIR, "a file, not a folder", destination)
    parent = os.path.dirname(os.path.abspath(destination))
    try:
        os.makedirs(parent, exist_ok=True)
        name = os.path.basename(os.path.abspath(destination))
        _remove_stale_staging(parent, name)
        staging = tempfile.mkdtemp(prefix=_staging_prefix(name, os.getpid()), dir=parent)
    except OSError as e:
        raise OSError(e.errno, e.strerror, destination) from None
    try:
        os.chmod(staging, 0o777 & ~_umask())  # mkdtemp's folder is its owner's alone
        yield staging
        _move_in(staging, destination)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
