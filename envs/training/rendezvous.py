"""How the hosts (nodes) of one training job find each other: ``ocean-warp train``'s ``--nnodes``, ``--node-rank``,
``--rdzv-endpoint`` and ``--rdzv-id`` checked, and the torchrun arguments they become.

Every host runs the same ``ocean-warp train ... --nnodes N --rdzv-endpoint HOST:PORT``; each starts torchrun
with its own ranks (``--gpus G``: G, else one), and the torchrun agents meet at the endpoint:

- without ``--node-rank``: torchrun's c10d rendezvous. The host whose name or address is HOST serves the
  rendezvous on PORT; torchrun numbers the hosts in the order of their descriptors, so global rank 0 (the one
  that writes every file) may be on any host. ``--nnodes MIN:MAX`` starts once MIN hosts have joined and takes
  up to MAX; a host that joins after the start makes torchrun restart every rank, which begins the training
  anew in a new run folder (continue with ``--resume``), so give MIN:MAX only to hosts started together.
- with ``--node-rank R``: torchrun's static rendezvous. Host R holds global ranks R G .. R G + G - 1, and
  host 0 (which must be HOST) holds rank 0 and writes the files.

Ranks learn who they are from torchrun's variables (``RANK``, ``LOCAL_RANK``, ``WORLD_SIZE``,
``LOCAL_WORLD_SIZE``, ``GROUP_RANK``): see :mod:`.distributed`.
"""

from __future__ import annotations

import dataclasses
import re

__all__ = ["DEFAULT_RUN_ID", "Rendezvous", "parse_nnodes", "parse_endpoint", "rendezvous_from_options"]

DEFAULT_RUN_ID = "ocean-warp-train"
"""``--rdzv-id`` when none is given: hosts meet only with others of the same id, so give each concurrent job
sharing an endpoint its own (a Slurm script: ``$SLURM_JOB_ID``)."""

_HOST = re.compile(r"^[A-Za-z0-9_.:-]+$")
_RUN_ID = re.compile(r"^[A-Za-z0-9_.-]+$")


@dataclasses.dataclass(frozen=True)
class Rendezvous:
    """The hosts of one job and where they meet."""

    min_nodes: int
    max_nodes: int
    """Hosts in the job: ``min_nodes`` to start, up to ``max_nodes`` (equal for a fixed count)."""
    host: str
    port: int
    """The rendezvous endpoint: a host of the job and a free TCP port on it."""
    run_id: str = DEFAULT_RUN_ID
    node_rank: int | None = None
    """This host's index, 0 .. nodes - 1 (static rendezvous); None: torchrun's c10d rendezvous numbers them."""

    @property
    def endpoint(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host  # an IPv6 address
        return f"{host}:{self.port}"

    @property
    def nnodes(self) -> str:
        """torchrun's ``--nnodes``: ``N`` or ``MIN:MAX``."""
        return str(self.min_nodes) if self.min_nodes == self.max_nodes else f"{self.min_nodes}:{self.max_nodes}"

    def torchrun_arguments(self) -> list[str]:
        """The arguments of torchrun (``python -m torch.distributed.run``) that join this rendezvous."""
        if self.node_rank is None:
            return [f"--nnodes={self.nnodes}", "--rdzv-backend=c10d", f"--rdzv-endpoint={self.endpoint}",
                    f"--rdzv-id={self.run_id}"]
        return [f"--nnodes={self.nnodes}", f"--node-rank={self.node_rank}", "--rdzv-backend=static",
                f"--rdzv-endpoint={self.endpoint}", f"--rdzv-id={self.run_id}"]


def parse_nnodes(text: str) -> tuple[int, int]:
    """``--nnodes``: ``"N"`` or ``"MIN:MAX"``, whole numbers >= 1 with MIN <= MAX, as (min, max).

    Raises:
        ValueError: one line naming the bad value.
    """
    parts = str(text).strip().split(":")
    bad = ValueError(f"--nnodes must be a whole number of hosts >= 1, or MIN:MAX with 1 <= MIN <= MAX, got {text!r}")
    if len(parts) > 2 or not all(re.fullmatch(r"\d+", part.strip()) for part in parts):
        raise bad
    low, high = int(parts[0]), int(parts[-1])
    if not 1 <= low <= high:
        raise bad
    return low, high


def parse_endpoint(text: str) -> tuple[str, int]:
    """``--rdzv-endpoint``: ``HOST:PORT`` (an IPv6 host in brackets, ``[::1]:29500``), PORT 1 .. 65535.

    Raises:
        ValueError: one line naming the bad value.
    """
    text = str(text).strip()
    found = re.fullmatch(r"\[([0-9A-Fa-f:.]+)\]:(\d+)|([^:\[\]]+):(\d+)", text)
    bad = (f"--rdzv-endpoint must be HOST:PORT, the address of one of the job's hosts and a free port on it "
           f"(e.g. node01:29500), got {text!r}")
    if found is None:
        raise ValueError(bad)
    host = found.group(1) or found.group(3)
    port = int(found.group(2) or found.group(4))
    if not _HOST.match(host):
        raise ValueError(bad)
    if not 1 <= port <= 65535:
        raise ValueError(f"--rdzv-endpoint {text}: the port must be in 1..65535, got {port}")
    return host, port


def rendezvous_from_options(nnodes: str | None, node_rank: int | None, endpoint: str | None,
                            run_id: str | None) -> Rendezvous | None:
    """The :class:`Rendezvous` of ``--nnodes``, ``--node-rank``, ``--rdzv-endpoint`` and ``--rdzv-id`` (each
    None where not given); None when none is given (one host).

    Raises:
        ValueError: one line naming what is wrong: a malformed value, a node rank outside 0 .. N - 1 or with
            ``MIN:MAX``, or ``--nnodes`` without an endpoint (or the others without ``--nnodes``).
    """
    if nnodes is None:
        given = [name for name, value in (("--node-rank", node_rank), ("--rdzv-endpoint", endpoint),
                                          ("--rdzv-id", run_id)) if value is not None]
        if given:
            verb = "applies" if len(given) == 1 else "apply"
            raise ValueError(f"{' and '.join(given)} only {verb} with several hosts: add --nnodes N")
        return None
    low, high = parse_nnodes(nnodes)
    if endpoint is None:
        raise ValueError(f"--nnodes {nnodes} needs --rdzv-endpoint HOST:PORT, where the hosts meet (one of them "
                         "and a free port on it, the same on every host)")
    host, port = parse_endpoint(endpoint)
    if run_id is not None and not _RUN_ID.match(run_id):
        raise ValueError(f"--rdzv-id must be letters, digits, '.', '_' or '-', got {run_id!r}")
    if node_rank is not None:
        if low != high:
            raise ValueError(f"--node-rank fixes each host's place, so it needs a fixed --nnodes N, not {nnodes}")
        if isinstance(node_rank, bool) or not isinstance(node_rank, int) or not 0 <= node_rank < high:
            raise ValueError(f"--node-rank must be in 0..{high - 1} (--nnodes {high}), got {node_rank!r}")
    return Rendezvous(low, high, host, port, run_id or DEFAULT_RUN_ID, node_rank)
