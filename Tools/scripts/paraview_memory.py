# pvpython Tools/scripts/paraview_memory.py PLUGIN [GRIDS LEVELS CELLS] [SIZE] [METHOD]
# Peak resident memory of a pvpython process showing the plugin's synthetic cosmology
# (AMR Cosmology (synthetic), the same hierarchy as amrsp's synthetic:cosmo) with the
# representation "AMR Single-Pass Volume" in a SIZE² render view: one still render after the
# source is in memory. Prints one JSON object: the process's resident memory before the source,
# with the source updated, and its peak after the render (VmHWM), the cell data's bytes, and the
# issue #19 bound 2 x cell data + 0.3 GB. Default: the paper's dataset-3 size at 512², the
# representation's Method "Auto" (METHOD: Auto, Packing, Bindless, Linear or Multi-Pass).
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvpython_exit import exit_keeping_output  # noqa: E402

from paraview import simple


def status_kib(field):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


plugin = sys.argv[1]
grids, levels, cells = (int(v) for v in (sys.argv[2:5] if len(sys.argv) >= 5
                                         else (39061, 13, 140000000)))
size = int(sys.argv[5]) if len(sys.argv) >= 6 else 512
method = sys.argv[6] if len(sys.argv) >= 7 else "Auto"
simple.LoadPlugin(plugin, remote=False, ns=globals())
before = status_kib("VmRSS")
source = AMRCosmologysynthetic(NumberOfGrids=grids, NumberOfLevels=levels, NumberOfCells=cells)
t0 = time.time()
source.UpdatePipeline()
generated = time.time() - t0
with_data = status_kib("VmRSS")
view = simple.CreateView("RenderView")
view.ViewSize = [size, size]
view.OrientationAxesVisibility = 0
display = simple.Show(source, view)
display.Representation = "AMR Single-Pass Volume"
display.Method = method
simple.ColorBy(display, ("CELLS", "Density"))
t0 = time.time()
simple.Render(view)
first_image = time.time() - t0
peak = status_kib("VmHWM")
info = source.GetDataInformation()
display.UpdatePropertyInformation()
cell_bytes = 4 * info.GetNumberOfCells()
print(json.dumps({
    "dataset": "AMR Cosmology (synthetic) grids=%d levels=%d cells=%d" % (grids, levels, cells),
    "image": [size, size],
    "method": method,
    "storage": display.GetProperty("SinglePassDataStorage").GetData(),
    "generation_s": round(generated, 3),
    "time_to_first_image_s": round(first_image, 3),
    "rss_before_source_bytes": before * 1024,
    "rss_with_source_bytes": with_data * 1024,
    "peak_rss_bytes": peak * 1024,
    "cell_data_bytes": cell_bytes,
    "bound_bytes": 2 * cell_bytes + 300 * 1000 * 1000,
    "peak_over_cell_data": round(peak * 1024 / cell_bytes, 3),
}))
exit_keeping_output(0)
