# pvpython test: the pvpython blocks of the README and docs/paraview.md run as written, from the
# source folder, on this ParaView. The only change made to a block is the plugin's path: the
# documents name the Debian 12 build's (build/paraview/lib/paraview-5.11/...), which becomes this
# configuration's build folder, relative to the source folder, as a user of it would type it.
# A block passes when it raises nothing, its display reports no render error, and the volume
# covers part of the view.
#
# Arguments: SOURCE_DIR PLUGIN DOCUMENT...
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import PluginTestKit as kit  # noqa: E402

DOCUMENTED_PLUGIN = "build/paraview/lib/paraview-5.11/plugins/SinglePassAMRPlugin/SinglePassAMRPlugin.so"

source_dir, plugin = sys.argv[1], sys.argv[2]
documents = sys.argv[3:]


def blocks(path):
    """The ```python blocks of `path` that load the plugin."""
    with open(path) as f:
        text = f.read()
    return [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "LoadPlugin(" in b]


def lit_share(view):
    """The share of the view's pixels that differ from its background."""
    from paraview.vtk.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

    grab = vtkWindowToImageFilter()
    grab.SetInput(view.GetRenderWindow())
    grab.ReadFrontBufferOff()
    grab.Update()
    pixels = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
    background = pixels[0]  # a corner, outside the volume
    return float((abs(pixels - background).max(axis=1) > 3).mean())


found = [(d, b) for d in documents for b in blocks(d)]
if len(found) < len(documents):
    kit.fail("expected a pvpython block that loads the plugin in each of %s, found %d"
             % (", ".join(documents), len(found)))
relative = os.path.relpath(plugin, source_dir)
os.chdir(source_dir)
for document, block in found:
    what = "the pvpython block of %s" % os.path.relpath(document, source_dir)
    if DOCUMENTED_PLUGIN not in block:
        kit.fail("%s does not load %s" % (what, DOCUMENTED_PLUGIN))
    for data in re.findall(r'FileNames=\["([^"]+)"', block):
        if not os.path.exists(data):
            kit.skip("%s reads %s, which is not here" % (what, data))
    code = block.replace(DOCUMENTED_PLUGIN, relative)
    print("%s, with the plugin at %s:\n%s" % (what, relative, code))
    namespace = {"__name__": "__documented__"}
    try:
        exec(compile(code, document, "exec"), namespace)
    except Exception as error:  # what the user would see: the block stops here
        kit.fail("%s raised %s: %s" % (what, type(error).__name__, error))
    display = namespace.get("display")
    simple = sys.modules["paraview.simple"]
    view = simple.GetActiveView()
    if display is None or view is None:
        kit.fail("%s left no display or view" % what)
    kit.check_window(view)
    display.SMProxy.UpdatePropertyInformation()
    kit.check_render_error(display.SMProxy.GetProperty("SinglePassRenderError").GetElement(0), what)
    share = lit_share(view)
    print("%s: the volume covers %.1f %% of the view" % (what, 100.0 * share))
    if share < 0.05:
        kit.fail("%s: the volume covers %.1f %% of the view (at least 5 %% expected)"
                 % (what, 100.0 * share))
    # the same count rejects the view without the volume
    simple.Hide(display.Input, view)
    simple.Render(view)
    empty = lit_share(view)
    if empty >= 0.01:
        kit.fail("%s: with the volume hidden %.1f %% of the view still counts as covered"
                 % (what, 100.0 * empty))
    # the next block shows its data in the same view (deleting a view and making another breaks
    # pvpython 5.11's X interactor)
    for proxy in list(simple.GetSources().values()):
        simple.Delete(proxy)
print("PASS")
