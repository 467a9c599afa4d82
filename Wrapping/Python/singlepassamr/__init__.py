# SPDX-License-Identifier: BSD-3-Clause
"""Single-pass GPU raycasting of structured AMR data (Kaehler & Abel 2013) for VTK's Python.

    from singlepassamr import vtkSinglePassAMRVolumeMapper

The classes of the VTK module AMRSP::SinglePassAMR (vtkSinglePassAMRVolumeMapper,
vtkMultiPassAMRVolumeMapper, vtkSinglePassAMRCosmoSource, ...), wrapped by VTK's own wrapper for
the VTK this package was built against; importing it imports the VTK modules it needs.
"""
from .vtkSinglePassAMR import *  # noqa: F401,F403
