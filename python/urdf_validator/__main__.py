"""``python -m urdf_validator``: the ``urdf_validate`` command."""

from ._cli import main

main()
