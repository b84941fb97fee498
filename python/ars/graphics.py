"""What the original ARS programs draw with (``ars.app.gp``): an engine and entities
(axes, boxes, spheres, cylinders, capsules, cones, meshes) that hold their shape, pose
and colour. They draw nothing by themselves: a simulation's own objects are drawn by
ARS's viewer, and these keep the programs that build and colour entities working
unchanged, with or without a display.
"""

__all__ = [
    "Axes",
    "Box",
    "Capsule",
    "Cone",
    "Cylinder",
    "Engine",
    "Entity",
    "ScreenshotRecorder",
    "Sphere",
    "Trimesh",
]


class Entity:
    """Something drawn: a pose and a colour."""

    def __init__(self, pos=(0, 0, 0), rot=None):
        self.position = tuple(pos)
        self.rotation = rot
        self.color = None

    @property
    def actor(self):
        return self

    def set_pose(self, pos, rot):
        self.position, self.rotation = tuple(pos), rot

    def set_color(self, color):
        self.color = tuple(color)

    def get_color(self):
        return self.color


class Axes(Entity):
    def __init__(self, pos=(0, 0, 0), rot=None, cylinder_radius=0.05):
        super().__init__(pos, rot)
        self.cylinder_radius = cylinder_radius


class Box(Entity):
    def __init__(self, size, pos, rot=None):
        super().__init__(pos, rot)
        self.size = tuple(size)


class Sphere(Entity):
    def __init__(self, radius, center, rot=None, phi_resolution=20, theta_resolution=20):
        super().__init__(center, rot)
        self.radius = radius


class Cylinder(Entity):
    def __init__(self, length, radius, center, rot=None, resolution=20):
        super().__init__(center, rot)
        self.length, self.radius = length, radius


class Capsule(Cylinder):
    pass


class Cone(Entity):
    def __init__(self, height, radius, center, rot=None, resolution=20):
        super().__init__(center, rot)
        self.height, self.radius = height, radius


class Trimesh(Entity):
    def __init__(self, vertices, faces, pos, rot=None):
        super().__init__(pos, rot)
        self.vertices, self.faces = vertices, faces


class Engine:
    """The drawing engine a program holds (``program.gAdapter``): the entities added."""

    def __init__(
        self,
        title,
        pos=None,
        size=(1000, 600),
        zoom=1.0,
        cam_position=(10, 8, 10),
        background_color=(0.1, 0.1, 0.4),
        **kwargs,
    ):
        self.title, self.size, self.zoom = title, size, zoom
        self.cam_position, self.background_color = cam_position, background_color
        self.objects = []
        # Set while ARS's viewer shows or records the program: writes the scene to a
        # PNG file (what the screenshot recorder uses).
        self.snapshot = None

    def add_object(self, obj):
        self.objects.append(obj)

    def remove_object(self, obj):
        if obj in self.objects:
            self.objects.remove(obj)

    def add_objects_list(self, objects):
        for obj in objects:
            self.add_object(obj)

    def reset(self):
        self.objects = []

    def finalize_window(self):
        pass


class ScreenshotRecorder:
    """Writes screenshots ``BASE<index>.png`` (every frame, or once a ``period`` of
    simulated time) while ARS's viewer shows or records the program; in a headless
    ``run`` nothing is written."""

    file_extension = "png"

    def __init__(self, base_filename="screenshot_", graphics_adapter=None):
        self.base_filename = base_filename
        self.gAdapter = graphics_adapter
        self.period = None
        self.last_write_time = None

    def calc_filename(self, index=1):
        return f"{self.base_filename}{index}.{self.file_extension}"

    def write(self, index=1, time=None):
        known = time is not None and self.period is not None and self.last_write_time is not None
        if known and time - self.last_write_time < self.period:
            return
        self.last_write_time = time
        snapshot = getattr(self.gAdapter, "snapshot", None)
        if snapshot is not None:
            snapshot(self.calc_filename(index))
