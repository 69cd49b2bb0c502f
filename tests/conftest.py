import os

# headless rendering: skip VTK's X attempt (STACK.md)
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
