"""The fixtures' link shapes: 16-sided prisms written as ASCII STL
(ur10e_like, panda_like)."""
import math

SIDES = 16


def prism_triangles(axis, start, end, radius, offset=(0, 0, 0)):
    """Triangles of a 16-sided prism of the given radius along axis ('x', 'y'
    or 'z') from start to end [m], shifted by offset."""
    def place(p):
        return tuple(p[i] + offset[i] for i in range(3))

    def point(t, a):
        u, v = radius * math.cos(a), radius * math.sin(a)
        return place({'x': (t, u, v), 'y': (v, t, u), 'z': (u, v, t)}[axis])
    c0 = place({'x': (start, 0, 0), 'y': (0, start, 0), 'z': (0, 0, start)}[axis])
    c1 = place({'x': (end, 0, 0), 'y': (0, end, 0), 'z': (0, 0, end)}[axis])
    tris = []
    for k in range(SIDES):
        a0, a1 = 2 * math.pi * k / SIDES, 2 * math.pi * (k + 1) / SIDES
        p00, p01, p10, p11 = point(start, a0), point(start, a1), point(end, a0), point(end, a1)
        tris += [(p00, p10, p11), (p00, p11, p01), (c0, p01, p00), (c1, p10, p11)]
    return tris


def write_stl(path, name, tris):
    with open(path, 'w') as f:
        f.write(f'solid {name}\n')
        for t in tris:
            f.write('  facet normal 0 0 0\n    outer loop\n')
            for p in t:
                f.write('      vertex %.6f %.6f %.6f\n' % p)
            f.write('    endloop\n  endfacet\n')
        f.write(f'endsolid {name}\n')
