# pvpython test: the plugin loads and its synthetic AMR source produces the requested hierarchy.
import sys

from paraview.simple import LoadPlugin

plugin = sys.argv[1]
LoadPlugin(plugin, remote=False, ns=globals())
source = AMRCosmologysynthetic(NumberOfGrids=60, NumberOfLevels=3, NumberOfCells=200000, Seed=2)
source.UpdatePipeline()
info = source.GetDataInformation()
kind = info.GetDataSetTypeAsString()
levels = info.DataInformation.GetNumberOfAMRLevels()
blocks = info.GetNumberOfDataSets()
print("plugin source: %s, %d levels, %d blocks" % (kind, levels, blocks))
if kind != "vtkOverlappingAMR" or levels != 3 or abs(blocks - 60) > 2:
    print("FAIL: unexpected output")
    sys.exit(1)
print("PASS")
