# The README's VTK Python example ("Using it from VTK Python"), run as written with the VTK
# configuration's Python (python3-vtk9 and this build's singlepassamr package on PYTHONPATH); the
# only change is the data folder, ../shared/data, made absolute. Its image must agree with the
# independent CPU reference (`amrsp reference`, no kD-tree) rendered from the example's own camera,
# transfer functions and background (--view-json): covered-pixel RMSE and coverage within bounds.
# The check then shows that it rejects the reference rendered with the colour and opacity log
# scales dropped (what a mapper that ignored them would draw).
#
# Arguments: README AMRSP DATA_DIR WORK_DIR
import json
import os
import re
import shutil
import subprocess
import sys

import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import PluginTestKit as kit  # noqa: E402  (plain Python: it imports nothing of ParaView)

readme, amrsp, data_dir, work = sys.argv[1:5]
RMSE_BOUND = 10.0     # 0-255, over the pixels covered in either image (measured 6.7: docs/python.md)
COVERAGE_BOUND = 0.02  # difference of the covered shares
MIN_COVERAGE = 0.05    # the least share of the image the volume must cover (measured 0.084)
REFERENCE_SAMPLE_FACTOR = 0.25  # the reference's step: a quarter of the finest cell edge


fail = kit.fail


def read_png(path):
    _, _, pixels = kit.read_png(path)
    if len(pixels) == 0:
        fail("cannot read %s" % path)
    return pixels


def compare(image, reference, background):
    """kit.rmse and kit.coverage over a background that is not black: a pixel is covered where it
    differs from the background by more than kit.BACKGROUND_LEVEL."""
    covered_image = (abs(image - background).max(axis=1) > kit.BACKGROUND_LEVEL)
    covered_reference = (abs(reference - background).max(axis=1) > kit.BACKGROUND_LEVEL)
    either = covered_image | covered_reference
    rmse = float(numpy.sqrt(((image[either] - reference[either]) ** 2).mean())) if either.any() else 0.0
    return rmse, float(covered_image.mean()), float(covered_reference.mean())


with open(readme) as f:
    text = f.read()
section = text[text.index("## Using it from VTK Python"):]
blocks = [b for b in re.findall(r"```python\n(.*?)```", section, re.S) if "from singlepassamr import" in b]
if len(blocks) != 1:
    fail("expected one python block importing singlepassamr in the README's VTK Python section, "
         "found %d" % len(blocks))
documented = "../shared/data"
if documented not in blocks[0]:
    fail("the example does not read its data from %s" % documented)
if not os.path.isdir(data_dir):
    kit.skip("the data folder %s is not here" % data_dir)  # a failure in CI (AMRSP_REQUIRE_GPU=1)
code = blocks[0].replace(documented, os.path.abspath(data_dir))
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
os.chdir(work)
print("the README's example, run in %s:\n%s" % (work, code))
namespace = {"__name__": "__readme__"}
exec(compile(code, readme, "exec"), namespace)

mapper, renderer = namespace["mapper"], namespace["renderer"]
error = mapper.GetLastError()
if error:
    fail("the mapper reports: %s" % error)
written = re.findall(r'SetFileName\("([^"]+\.png)"\)', code)
if not written or not os.path.exists(written[-1]):
    fail("the example wrote no image (%s)" % written)
image = read_png(written[-1])
print("class %s from %s" % (mapper.GetClassName(), sys.modules["singlepassamr"].__file__))

camera = renderer.GetActiveCamera()
colours, opacity = namespace["colours"], namespace["opacity"]
rgb = []
for i in range(colours.GetSize()):
    node = [0.0] * 6
    colours.GetNodeValue(i, node)
    rgb.append(node[:4])
alpha = []
for i in range(opacity.GetSize()):
    node = [0.0] * 4
    opacity.GetNodeValue(i, node)
    alpha.append(node[:2])
view = {
    "camera": {"position": list(camera.GetPosition()), "focal_point": list(camera.GetFocalPoint()),
               "view_up": list(camera.GetViewUp()), "view_angle": camera.GetViewAngle(),
               "parallel_projection": bool(camera.GetParallelProjection()),
               "parallel_scale": camera.GetParallelScale()},
    "transfer_function": {"rgb_points": rgb, "opacity_points": alpha,
                          "unit_distance": namespace["volume_property"].GetScalarOpacityUnitDistance(),
                          "color_log_scale": colours.GetScale() == 1,
                          "opacity_log_scale": bool(opacity.GetUseLogScale())},
    "background": list(renderer.GetBackground()),
}
size = namespace["window"].GetSize()
dataset = re.findall(r'reader.SetFileName\("([^"]+)"\)', code)[0]
array = re.findall(r'SelectScalarArray\("([^"]+)"\)', code)[0]


def reference(name, view):
    path = os.path.join(work, name + ".json")
    with open(path, "w") as f:
        json.dump(view, f)
    out = os.path.join(work, name + ".png")
    run = subprocess.run([amrsp, "reference", dataset, "--array", array, "--view-json", path,
                          "--size", "%dx%d" % tuple(size), "--reference-sample-factor",
                          str(REFERENCE_SAMPLE_FACTOR), "-o", out],
                         capture_output=True, text=True)
    if run.returncode != 0:
        fail("amrsp reference failed:\n%s%s" % (run.stdout, run.stderr))
    return read_png(out)


background = numpy.array(view["background"]) * 255.0
rmse, share, reference_share = compare(image, reference("reference", view), background)
good = rmse < RMSE_BOUND and abs(share - reference_share) < COVERAGE_BOUND and share > MIN_COVERAGE
print("%s: against the CPU reference: covered RMSE %.2f (bound %.1f), covered %.3f of the image, "
      "the reference %.3f (bound %.2f apart)" % ("ok" if good else "FAIL", rmse, RMSE_BOUND, share,
                                                 reference_share, COVERAGE_BOUND))
linear = json.loads(json.dumps(view))
linear["transfer_function"]["color_log_scale"] = False
linear["transfer_function"]["opacity_log_scale"] = False
wrong_rmse, _, wrong_share = compare(image, reference("reference-linear", linear), background)
rejected = wrong_rmse >= RMSE_BOUND or abs(share - wrong_share) >= COVERAGE_BOUND
print("%s: the reference without the log scales is rejected: covered RMSE %.2f, covered %.3f"
      % ("ok" if rejected else "FAIL", wrong_rmse, wrong_share))
# the camera turned by 2 degrees about the view-up axis through the focal point (camera plumbing)
turned = json.loads(json.dumps(view))
position = numpy.array(view["camera"]["position"])
focus = numpy.array(view["camera"]["focal_point"])
axis = numpy.array(view["camera"]["view_up"]) / numpy.linalg.norm(view["camera"]["view_up"])
angle = numpy.radians(2.0)
offset = position - focus
offset = (offset * numpy.cos(angle) + numpy.cross(axis, offset) * numpy.sin(angle)
          + axis * numpy.dot(axis, offset) * (1 - numpy.cos(angle)))
turned["camera"]["position"] = list(focus + offset)
turned_rmse, _, turned_share = compare(image, reference("reference-turned", turned), background)
turned_rejected = turned_rmse >= RMSE_BOUND or abs(share - turned_share) >= COVERAGE_BOUND
print("%s: the reference of the camera turned by 2 degrees is rejected: covered RMSE %.2f, covered "
      "%.3f" % ("ok" if turned_rejected else "FAIL", turned_rmse, turned_share))
ok = good and rejected and turned_rejected
print("PASS" if ok else "FAIL")
kit.leave(0 if ok else 1)
