/* SPDX-License-Identifier: BSD-3-Clause
 *
 * A driver that runs out of memory, for the tests: loaded with LD_PRELOAD, this library hands
 * VTK (which loads OpenGL through glXGetProcAddress, eglGetProcAddress or OSMesaGetProcAddress)
 * a glTexImage3D that refuses every 3D texture of more than AMRSP_REFUSE_TEXELS texels, and a
 * glTexImage2D that refuses every 2D texture of more than AMRSP_REFUSE_TEXELS_2D texels, the way
 * a driver refuses an allocation it cannot make: nothing is allocated and glGetError reports
 * GL_OUT_OF_MEMORY (0x0505) once. Smaller textures and every other function are the driver's.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

typedef void (*Function)(void);
typedef void (*TexImage3D)(unsigned int target, int level, int internalFormat, int width,
  int height, int depth, int border, unsigned int format, unsigned int type, const void* pixels);
typedef unsigned int (*GetError)(void);
typedef void (*TexImage2D)(unsigned int target, int level, int internalFormat, int width,
  int height, int border, unsigned int format, unsigned int type, const void* pixels);

/* Tells a test that the library is loaded, and whether VTK took glTexImage3D from it: VTK 9.1
 * and 9.2 (GLEW) and 9.3 on GLX through the loaders wrapped below; VTK's run-time EGL and OSMesa
 * loaders (9.4 on) resolve OpenGL with dlsym, which this library wraps too. */
int amrsp_refuse_large_textures_loaded = 1;
int amrsp_refuse_large_textures_active = 0;
/* Whether VTK's glTexImage2D calls come here: through a wrapped loader (glad) or, with GLEW,
 * which links OpenGL 1.1 functions directly, once the symbol below has been called. */
int amrsp_refuse_large_textures_2d_active = 0;

typedef void* (*Dlsym)(void* handle, const char* name);

/* glibc's own dlsym (this library exports a dlsym of its own, below, so its calls go here) */
static void* RealDlsym(void* handle, const char* name)
{
  static Dlsym real;
  if (!real)
  {
    real = (Dlsym)dlvsym(RTLD_NEXT, "dlsym", "GLIBC_2.34");
    if (!real)
    {
      real = (Dlsym)dlvsym(RTLD_NEXT, "dlsym", "GLIBC_2.2.5");
    }
  }
  return real ? real(handle, name) : 0;
}

static TexImage3D RealTexImage3D;
static TexImage2D RealTexImage2D;
static GetError RealGetError;
static unsigned int PendingError;
static const unsigned int OutOfMemory = 0x0505;

static void RefusingTexImage3D(unsigned int target, int level, int internalFormat, int width,
  int height, int depth, int border, unsigned int format, unsigned int type, const void* pixels)
{
  const char* limit = getenv("AMRSP_REFUSE_TEXELS");
  if (limit && (double)width * height * depth > atof(limit))
  {
    PendingError = OutOfMemory;
    return;
  }
  RealTexImage3D(target, level, internalFormat, width, height, depth, border, format, type, pixels);
}

static void RefusingTexImage2D(unsigned int target, int level, int internalFormat, int width,
  int height, int border, unsigned int format, unsigned int type, const void* pixels)
{
  const char* limit = getenv("AMRSP_REFUSE_TEXELS_2D");
  if (limit && (double)width * height > atof(limit))
  {
    PendingError = OutOfMemory;
    return;
  }
  RealTexImage2D(target, level, internalFormat, width, height, border, format, type, pixels);
}

static unsigned int ReportingGetError(void)
{
  if (PendingError)
  {
    const unsigned int error = PendingError;
    PendingError = 0;
    return error;
  }
  return RealGetError();
}

/* The function `name` as `real` (the driver's loader) returns it, or its refusing stand-in. */
static Function Substitute(const char* name, Function real)
{
  if (!real || !name)
  {
    return real;
  }
  if (strcmp(name, "glTexImage3D") == 0)
  {
    RealTexImage3D = (TexImage3D)real;
    amrsp_refuse_large_textures_active = 1;
    return (Function)RefusingTexImage3D;
  }
  if (strcmp(name, "glTexImage2D") == 0)
  {
    RealTexImage2D = (TexImage2D)real;
    amrsp_refuse_large_textures_2d_active = 1;
    return (Function)RefusingTexImage2D;
  }
  if (strcmp(name, "glGetError") == 0)
  {
    RealGetError = (GetError)real;
    return (Function)ReportingGetError;
  }
  return real;
}

/* GLEW (VTK up to 9.2) links OpenGL 1.1 functions such as glGetError directly. */
unsigned int glGetError(void)
{
  if (!RealGetError)
  {
    RealGetError = (GetError)RealDlsym(RTLD_NEXT, "glGetError");
  }
  return ReportingGetError();
}

/* GLEW (VTK up to 9.2) links glTexImage2D directly too. */
void glTexImage2D(unsigned int target, int level, int internalFormat, int width, int height,
  int border, unsigned int format, unsigned int type, const void* pixels)
{
  if (!RealTexImage2D)
  {
    RealTexImage2D = (TexImage2D)RealDlsym(RTLD_NEXT, "glTexImage2D");
  }
  amrsp_refuse_large_textures_2d_active = 1;
  RefusingTexImage2D(target, level, internalFormat, width, height, border, format, type, pixels);
}

/* The drivers' loaders, wrapped: each takes the real one from the library VTK asked with dlsym
 * (below), or else the next one after this library. */
typedef Function (*Loader)(const char*);
#define AMRSP_WRAP_LOADER(loader)                                                                  \
  static Loader Real_##loader;                                                                     \
  Function loader(const char* name)                                                                \
  {                                                                                                \
    if (!Real_##loader)                                                                            \
    {                                                                                              \
      Real_##loader = (Loader)RealDlsym(RTLD_NEXT, #loader);                                       \
    }                                                                                              \
    return Substitute(name, Real_##loader ? Real_##loader(name) : 0);                              \
  }

AMRSP_WRAP_LOADER(glXGetProcAddress)
AMRSP_WRAP_LOADER(glXGetProcAddressARB)
AMRSP_WRAP_LOADER(eglGetProcAddress)
AMRSP_WRAP_LOADER(OSMesaGetProcAddress)

/* A loader VTK took with dlsym: remembered as the real one, answered with its wrapper. */
static void* WrapLoader(const char* name, void* found)
{
#define AMRSP_LOADER_CASE(loader)                                                                  \
  if (strcmp(name, #loader) == 0)                                                                  \
  {                                                                                                \
    if (!Real_##loader)                                                                            \
    {                                                                                              \
      Real_##loader = (Loader)found;                                                               \
    }                                                                                              \
    return (void*)loader;                                                                          \
  }
  AMRSP_LOADER_CASE(glXGetProcAddress)
  AMRSP_LOADER_CASE(glXGetProcAddressARB)
  AMRSP_LOADER_CASE(eglGetProcAddress)
  AMRSP_LOADER_CASE(OSMesaGetProcAddress)
#undef AMRSP_LOADER_CASE
  return found;
}

/* VTK's run-time loaders (glad, VTK 9.4 on) take OpenGL's functions from the driver's library
 * with dlsym: the three functions above are substituted there too; every other symbol is
 * glibc's answer. */
void* dlsym(void* handle, const char* name)
{
  void* found = RealDlsym(handle, name);
  if (!found) /* name is never null: glibc declares it nonnull */
  {
    return found;
  }
  if (strstr(name, "GetProcAddress"))
  {
    return WrapLoader(name, found); /* glad's loaders take the driver's loader this way */
  }
  if (strncmp(name, "gl", 2) != 0)
  {
    return found;
  }
  return (void*)Substitute(name, (Function)found);
}
