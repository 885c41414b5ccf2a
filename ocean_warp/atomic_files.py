"""Write files so that a reader never sees half of one and a crash never destroys the old version."""

from __future__ import annotations

import contextlib
import os
import tempfile

__all__ = ["atomic_output", "save_figure"]


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike, suffix: str = ""):
    """Yield a temporary path beside ``path``; on success it replaces ``path`` in one rename.
    ``suffix`` (e.g. ".png") lets writers that look at the file extension pick the format."""
    path = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=directory, prefix=".tmp-", suffix=suffix or os.path.splitext(path)[1])
    os.close(handle)
    try:
        yield temporary
        # mkstemp creates the file private (0600); give it the mode any new file of the user's gets.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.remove(temporary)
        raise


def save_figure(figure, path: str | os.PathLike, *, dpi: int = 110) -> None:
    """Write a matplotlib ``figure`` to ``path`` as a PNG of ``dpi`` dots per inch, atomically, and close it
    (also when writing fails)."""
    import matplotlib.pyplot as plt

    try:
        with atomic_output(path, suffix=".png") as temporary:
            figure.savefig(temporary, dpi=dpi, format="png")
    finally:
        plt.close(figure)
