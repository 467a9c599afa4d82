# pvpython test of the representation's progress:
#
#   pvpython --force-offscreen-rendering TestPluginProgress.py PLUGIN
#
# The mapper builds and uploads its textures inside the view's render. ParaView registers the
# representation (not its mappers) with its progress handler (vtkSIProxy::CreateVTKObjects), and
# the GUI brackets every render of a view with the session's PrepareProgress and
# CleanupPendingProgress (pqView::forceRender); the handler forwards what it hears in between to
# the GUI's progress bar (pqProgressManager -> pqProgressWidget, repainted at once). Checks:
# - the representation's own ProgressEvents during the first render go from 0 to 1 without going
#   back (the build in [0, 0.5], the upload in [0.5, 1]), texts "AMR Single-Pass Volume: STEP"
#   through every step of the build and the upload, in order;
# - rendering as the GUI does (PrepareProgress, Render, CleanupPendingProgress), the session's
#   progress handler hears them: at least one "AMR Single-Pass Volume: ..." event, in order;
# - a camera change (nothing rebuilt) reports none.
# Exit codes: 0 pass, 1 fail, 125 skipped (no X display or no usable OpenGL context).
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import check_render_error, fail  # noqa: E402

PREFIX = "AMR Single-Pass Volume: "
# the mapper's steps in order (vtkSinglePassAMRVolumeMapper::BuildData, PrepareRayCasting, upload)
PHASES = ["converting the AMR blocks", "kD-tree", "encoding the kD-tree",
          "the data nodes' value ranges", "packing the bricks", "the scalar range", "done",
          "uploading the grid data"]


def run_problem(events):
    """'' when `events` [(fraction, phase)] go from 0 to 1, never back, through PHASES in order."""
    if not events:
        return "no ProgressEvent"
    if events[0][0] != 0.0 or events[-1][0] != 1.0:
        return "from %.3f to %.3f, not from 0 to 1" % (events[0][0], events[-1][0])
    order = []
    for i, (fraction, phase) in enumerate(events):
        if i and fraction < events[i - 1][0]:
            return "event %d goes back from %.3f to %.3f" % (i, events[i - 1][0], fraction)
        if phase not in PHASES:
            return "unknown phase %r" % phase
        if phase not in order:
            order.append(phase)
    if order != PHASES:
        return "phases in the order %s" % order
    return ""


def main():
    plugin = sys.argv[1]
    from PluginTestKit import info_property, require_display

    require_display()
    from paraview import servermanager, simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    # large enough for an atlas of several upload slabs (16 MiB each)
    source = AMRCosmologysynthetic(NumberOfGrids=300, NumberOfLevels=4, NumberOfCells=8000000,
                                   Seed=11)
    view = simple.CreateView("RenderView")
    view.ViewSize = [96, 96]
    display = simple.Show(source, view)
    display.Representation = "AMR Single-Pass Volume"
    simple.ColorBy(display, ("CELLS", "Density"))

    # the representation's own events (what ParaView's progress handler observes)
    representation = display.GetClientSideObject().GetActiveRepresentation()
    own = []

    def on_own(caller, event):
        text = caller.GetProgressText() or ""
        if text.startswith(PREFIX):
            own.append((caller.GetProgress(), text[len(PREFIX):]))

    representation.AddObserver("ProgressEvent", on_own)

    # what the session's progress handler passes on to the GUI (LastProgress in percent)
    session = servermanager.ActiveConnection.Session
    handler = session.GetProgressHandler()
    handler.SetProgressInterval(0.01)  # the client's default is 0.1 s: keep more of the events
    heard = []

    def on_handler(caller, event):
        heard.append((caller.GetLastProgress(), caller.GetLastProgressText() or ""))

    handler.AddObserver("ProgressEvent", on_handler)

    session.PrepareProgress()  # as pqView::forceRender
    simple.Render(view)
    session.CleanupPendingProgress()
    check_render_error(info_property(display, "SinglePassRenderError"), "the first render")

    starts = [(round(f, 3), p) for i, (f, p) in enumerate(own) if i == 0 or p != own[i - 1][1]]
    print("representation: %d ProgressEvents; phases start at %s" % (len(own), starts))
    problem = run_problem(own)
    if problem:
        fail("the representation's progress during the first render: " + problem)
    ours = [(percent, text[len(PREFIX):]) for percent, text in heard if text.startswith(PREFIX)]
    print("progress handler: %d events, %d of them the representation's: %s"
          % (len(heard), len(ours), ours))
    if not ours:
        fail("the session's progress handler heard nothing of the representation's progress")
    if any(ours[i][0] < ours[i - 1][0] for i in range(1, len(ours))):
        fail("the progress handler's percentages go back")
    if any(phase not in PHASES for _, phase in ours):
        fail("the progress handler heard an unknown phase")
    # the checker rejects a run that goes back and one without a phase
    if not run_problem(own[:1] + own[2:] + own[1:2]) or not run_problem(
            [e for e in own if e[1] != "packing the bricks"]):
        fail("the check does not reject broken runs")

    del own[:]
    session.PrepareProgress()
    view.GetActiveCamera().Azimuth(40.0)
    simple.Render(view)
    session.CleanupPendingProgress()
    print("after a camera change: %d ProgressEvents" % len(own))
    if own:
        fail("a camera change (nothing rebuilt) reported progress")
    print("PASS")


if __name__ == "__main__":
    main()
