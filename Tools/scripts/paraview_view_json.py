# What `amrsp reference --view-json` needs to render a ParaView view as it shows a volume: used
# by the plugin's tests and the in-situ example's Catalyst script. Imports ParaView only inside
# the functions.


def first_light(view):
    """The light the mapper shades with: the view renderer's first switched-on light (ParaView's
    light kit: its key light), in world coordinates, colour = diffuse colour x intensity."""
    lights = view.GetRenderer().GetLights()
    lights.InitTraversal()
    light = lights.GetNextItem()
    while light is not None and not light.GetSwitch():
        light = lights.GetNextItem()
    if light is None:
        return None
    intensity = light.GetIntensity()
    return {
        "position": list(light.GetTransformedPosition()),
        "focal_point": list(light.GetTransformedFocalPoint()),
        "positional": bool(light.GetPositional()),
        "colour": [c * intensity for c in light.GetDiffuseColor()],
    }


def write_view_json(view, display, array, path, iso_values=None):
    """Writes what `amrsp reference --view-json` needs to render the view as ParaView shows it:
    the camera, the colour map and opacity function of `array` (the reference's are linear
    between points, so every opacity point must have midpoint 0.5 and sharpness 0), the unit
    distance, the background, the light and material of the shading, and `iso_values`."""
    import json
    from paraview import simple

    lut = simple.GetColorTransferFunction(array)
    pwf = simple.GetOpacityTransferFunction(array)
    for i in range(0, len(pwf.Points), 4):
        if abs(pwf.Points[i + 2] - 0.5) > 1e-12 or abs(pwf.Points[i + 3]) > 1e-12:
            raise ValueError("opacity point %d is not linear (midpoint/sharpness)" % (i // 4))
    cam = view.GetActiveCamera()
    view_json = {
        "camera": {
            "position": list(cam.GetPosition()),
            "focal_point": list(cam.GetFocalPoint()),
            "view_up": list(cam.GetViewUp()),
            "view_angle": cam.GetViewAngle(),
            "parallel_projection": bool(cam.GetParallelProjection()),
            "parallel_scale": cam.GetParallelScale(),
        },
        "transfer_function": {
            "rgb_points": [list(lut.RGBPoints[i:i + 4]) for i in range(0, len(lut.RGBPoints), 4)],
            "opacity_points": [list(pwf.Points[i:i + 2]) for i in range(0, len(pwf.Points), 4)],
            "unit_distance": display.ScalarOpacityUnitDistance,
            "color_log_scale": bool(lut.UseLogScale),
            "opacity_log_scale": bool(pwf.UseLogScale),
        },
        "background": list(view.Background),
        "material": {"ambient": display.Ambient, "diffuse": display.Diffuse,
                     "specular": display.Specular, "specular_power": display.SpecularPower},
    }
    # no switched-on light: the mapper shades with the ambient term alone
    view_json["light"] = first_light(view) or {
        "position": list(cam.GetPosition()), "focal_point": list(cam.GetFocalPoint()),
        "positional": False, "colour": [0.0, 0.0, 0.0]}
    if iso_values:
        view_json["iso_values"] = list(iso_values)
    with open(path, "w") as f:
        json.dump(view_json, f, indent=2)
