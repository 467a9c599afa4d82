# Small X11 helper for documentation screenshots (Xlib and XTest through ctypes, VTK's PNG
# writer; no ImageMagick, xwd or xdotool needed). On a display without a window manager:
#   DISPLAY=:97 pvpython scripts/x11-tool.py grab OUT.png [WIDTH]   root window -> PNG (shrunk)
#   DISPLAY=:97 pvpython scripts/x11-tool.py maximize              largest top-level window
#                                                                   -> the whole screen
#   DISPLAY=:97 pvpython scripts/x11-tool.py click X Y              left click at (X, Y)
#   DISPLAY=:97 pvpython scripts/x11-tool.py drag X0 Y0 X1 Y1       left-button drag
import ctypes
import ctypes.util
import sys

from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkImagingCore import vtkImageResize
from vtkmodules.util.numpy_support import numpy_to_vtk
import numpy


class XImage(ctypes.Structure):
    # the leading fields of Xlib's XImage
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int),
                ("format", ctypes.c_int), ("data", ctypes.c_void_p),
                ("byte_order", ctypes.c_int), ("bitmap_unit", ctypes.c_int),
                ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int),
                ("depth", ctypes.c_int), ("bytes_per_line", ctypes.c_int),
                ("bits_per_pixel", ctypes.c_int)]


x11 = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11"))
x11.XOpenDisplay.restype = ctypes.c_void_p
x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
x11.XDefaultRootWindow.restype = ctypes.c_ulong
x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
x11.XDisplayWidth.argtypes = [ctypes.c_void_p, ctypes.c_int]
x11.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
x11.XGetImage.restype = ctypes.POINTER(XImage)
x11.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int,
                          ctypes.c_uint, ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
x11.XCloseDisplay.argtypes = [ctypes.c_void_p]

x11.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_ulong),
                          ctypes.POINTER(ctypes.c_ulong), ctypes.POINTER(ctypes.c_void_p),
                          ctypes.POINTER(ctypes.c_uint)]
x11.XMoveResizeWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int,
                                  ctypes.c_uint, ctypes.c_uint]
x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]


class XWindowAttributes(ctypes.Structure):
    # the leading fields of Xlib's XWindowAttributes (enough for the size and map state)
    _fields_ = [("x", ctypes.c_int), ("y", ctypes.c_int), ("width", ctypes.c_int),
                ("height", ctypes.c_int), ("border_width", ctypes.c_int), ("depth", ctypes.c_int),
                ("visual", ctypes.c_void_p), ("root", ctypes.c_ulong), ("class_", ctypes.c_int),
                ("bit_gravity", ctypes.c_int), ("win_gravity", ctypes.c_int),
                ("backing_store", ctypes.c_int), ("backing_planes", ctypes.c_ulong),
                ("backing_pixel", ctypes.c_ulong), ("save_under", ctypes.c_int),
                ("colormap", ctypes.c_ulong), ("map_installed", ctypes.c_int),
                ("map_state", ctypes.c_int), ("all_event_masks", ctypes.c_long),
                ("your_event_mask", ctypes.c_long), ("do_not_propagate_mask", ctypes.c_long),
                ("override_redirect", ctypes.c_int), ("screen", ctypes.c_void_p)]


x11.XGetWindowAttributes.argtypes = [ctypes.c_void_p, ctypes.c_ulong,
                                     ctypes.POINTER(XWindowAttributes)]


def open_display():
    display = x11.XOpenDisplay(None)
    if not display:
        sys.exit("x11-tool: cannot open the X display")
    return display


def maximize():
    display = open_display()
    root = x11.XDefaultRootWindow(display)
    root_return, parent = ctypes.c_ulong(), ctypes.c_ulong()
    children, count = ctypes.c_void_p(), ctypes.c_uint()
    x11.XQueryTree(display, root, ctypes.byref(root_return), ctypes.byref(parent),
                   ctypes.byref(children), ctypes.byref(count))
    windows = ctypes.cast(children, ctypes.POINTER(ctypes.c_ulong))
    best, best_area = None, 0
    for i in range(count.value):
        attributes = XWindowAttributes()
        x11.XGetWindowAttributes(display, windows[i], ctypes.byref(attributes))
        area = attributes.width * attributes.height
        if attributes.map_state == 2 and area > best_area:  # IsViewable
            best, best_area = windows[i], area
    if best is None:
        sys.exit("x11-tool: no mapped top-level window")
    x11.XMoveResizeWindow(display, best, 0, 0, x11.XDisplayWidth(display, 0),
                          x11.XDisplayHeight(display, 0))
    x11.XSync(display, 0)
    x11.XCloseDisplay(display)


def click(x, y, to=None):
    xtst = ctypes.cdll.LoadLibrary(ctypes.util.find_library("Xtst"))
    xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int,
                                          ctypes.c_int, ctypes.c_ulong]
    xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int,
                                          ctypes.c_ulong]
    display = open_display()
    xtst.XTestFakeMotionEvent(display, 0, x, y, 0)
    xtst.XTestFakeButtonEvent(display, 1, 1, 0)
    if to is not None:
        # in steps, so that the widget under the pointer follows the drag
        for i in range(1, 11):
            x11.XSync(display, 0)
            xtst.XTestFakeMotionEvent(display, 0, x + (to[0] - x) * i // 10,
                                      y + (to[1] - y) * i // 10, 20)
    xtst.XTestFakeButtonEvent(display, 1, 0, 0)
    x11.XSync(display, 0)
    x11.XCloseDisplay(display)


def grab(path, shrink_to=None):
    display = open_display()
    width, height = x11.XDisplayWidth(display, 0), x11.XDisplayHeight(display, 0)
    ZPixmap, AllPlanes = 2, 0xFFFFFFFF
    image = x11.XGetImage(display, x11.XDefaultRootWindow(display), 0, 0, width, height, AllPlanes,
                          ZPixmap).contents
    if image.bits_per_pixel != 32:
        sys.exit("x11-tool: only 32-bit pixels are handled, got %d" % image.bits_per_pixel)
    raw = ctypes.string_at(image.data, image.bytes_per_line * height)
    pixels = numpy.frombuffer(raw, dtype=numpy.uint8).reshape(height, image.bytes_per_line // 4, 4)
    rgb = pixels[:, :width, 2::-1]  # BGRX (little-endian TrueColor) -> RGB
    rgb = numpy.ascontiguousarray(rgb[::-1])  # X rows go down, VTK rows go up
    x11.XCloseDisplay(display)

    data = vtkImageData()
    data.SetDimensions(width, height, 1)
    data.GetPointData().SetScalars(numpy_to_vtk(rgb.reshape(-1, 3), deep=1))
    source = data
    if shrink_to and shrink_to < width:
        resize = vtkImageResize()
        resize.SetInputData(data)
        resize.SetOutputDimensions(shrink_to, int(round(height * shrink_to / width)), 1)
        resize.Update()
        source = resize.GetOutput()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetCompressionLevel(9)
    writer.SetInputData(source)
    writer.Write()
    print("x11-tool: %s (%dx%d screen)" % (path, width, height))


if __name__ == "__main__":
    command = sys.argv[1] if len(sys.argv) > 1 else ""
    if command == "grab" and len(sys.argv) in (3, 4):
        grab(sys.argv[2], int(sys.argv[3]) if len(sys.argv) == 4 else None)
    elif command == "maximize" and len(sys.argv) == 2:
        maximize()
    elif command == "click" and len(sys.argv) == 4:
        click(int(sys.argv[2]), int(sys.argv[3]))
    elif command == "drag" and len(sys.argv) == 6:
        click(int(sys.argv[2]), int(sys.argv[3]), (int(sys.argv[4]), int(sys.argv[5])))
    else:
        sys.exit("usage: x11-tool.py grab OUT.png [WIDTH] | maximize | click X Y | "
                 "drag X0 Y0 X1 Y1")
