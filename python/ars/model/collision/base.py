"""Terrain helpers of the original ARS API (``ars.model.collision.base``)."""

__all__ = ["HeightfieldTrimesh"]


class HeightfieldTrimesh:
    """A height field as a triangle mesh: a grid of ``size_x × size_z`` vertices
    (vertex ``(x, z)`` at index ``size_z · x + z``), two triangles per cell."""

    @staticmethod
    def calc_faces(size_x, size_z):
        """The triangles of the grid, as vertex-index triples, cell by cell (``x``
        outer, ``z`` inner). The diagonal alternates from cell to cell so that the
        mesh has no preferred direction.

        >>> HeightfieldTrimesh.calc_faces(2, 4)
        [(0, 1, 4), (1, 5, 4), (1, 6, 5), (1, 2, 6), (2, 3, 6), (3, 7, 6)]
        """
        faces = []
        parity = 0 if size_z % 2 else 1
        for x in range(size_x - 1):
            for z in range(size_z - 1):
                i00 = size_z * x + z
                i01, i10 = i00 + 1, i00 + size_z
                i11 = i10 + 1
                if (i00 + parity) % 2 == 0:
                    faces += [(i00, i11, i10), (i00, i01, i11)]
                else:
                    faces += [(i00, i01, i10), (i01, i11, i10)]
        return faces
