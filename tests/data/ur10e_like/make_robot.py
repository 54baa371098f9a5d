#!/usr/bin/env python3
"""Writes ur10e_like.urdf and its meshes (ASCII STL prisms, 16 sides): a
UR10e-sized arm whose mid-range pose (q = 0) holds it horizontally with the
shoulder axis 0.16 m above the floor and the wrist 1.5 cm above it; effort and
velocity limits as UR10e's data sheet. Deterministic; run from this folder."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
from prism_stl import prism_triangles, write_stl  # noqa: E402


# link: (mesh axis, start, end, radius, mass, centre of mass)
LINKS = {
    'base_link': ('z', 0.0, 0.10, 0.09, 4.0, (0, 0, 0.05)),
    'shoulder_link': ('z', 0.0, 0.06, 0.075, 7.4, (0, 0, 0.03)),
    'upper_arm_link': ('x', 0.0, 0.61, 0.055, 12.7, (0.30, 0, 0)),
    'forearm_link': ('x', 0.0, 0.57, 0.045, 4.3, (0.28, 0, 0)),
    'wrist_1_link': ('y', 0.0, 0.11, 0.04, 2.0, (0, 0.06, 0)),
    'wrist_2_link': ('z', -0.11, 0.0, 0.04, 2.0, (0, 0, -0.06)),
    'wrist_3_link': ('y', 0.0, 0.09, 0.035, 0.6, (0, 0.045, 0)),
}
# joint: (parent, child, origin, axis, effort [N m], velocity [rad/s])
JOINTS = [
    ('shoulder_pan_joint', 'base_link', 'shoulder_link', (0, 0, 0.10), 'z', 330, 2.094),
    ('shoulder_lift_joint', 'shoulder_link', 'upper_arm_link', (0, 0, 0.06), 'y', 330, 2.094),
    ('elbow_joint', 'upper_arm_link', 'forearm_link', (0.61, 0, 0), 'y', 150, 3.142),
    ('wrist_1_joint', 'forearm_link', 'wrist_1_link', (0.57, 0, 0), 'y', 56, 3.142),
    ('wrist_2_joint', 'wrist_1_link', 'wrist_2_link', (0, 0.11, 0), 'z', 56, 3.142),
    ('wrist_3_joint', 'wrist_2_link', 'wrist_3_link', (0, 0, -0.11), 'y', 56, 3.142),
]
AXES = {'x': '1 0 0', 'y': '0 1 0', 'z': '0 0 1'}


def inertia(axis, start, end, radius, mass):
    """Solid cylinder about its centre of mass: (ixx, iyy, izz)."""
    length = abs(end - start)
    along, across = 0.5 * mass * radius ** 2, mass * (3 * radius ** 2 + length ** 2) / 12
    return tuple(along if a == axis else across for a in 'xyz')


def main():
    out = ['<?xml version="1.0"?>', '<robot name="ur10e_like">']
    for name, (axis, start, end, radius, mass, com) in LINKS.items():
        write_stl(f'meshes/{name}.stl', name, prism_triangles(axis, start, end, radius))
        ixx, iyy, izz = inertia(axis, start, end, radius, mass)
        mesh = f'<geometry><mesh filename="meshes/{name}.stl"/></geometry>'
        out += [f'  <link name="{name}">',
                f'    <inertial><origin xyz="{com[0]} {com[1]} {com[2]}"/><mass value="{mass}"/>'
                f'<inertia ixx="{ixx:.6g}" ixy="0" ixz="0" iyy="{iyy:.6g}" iyz="0" izz="{izz:.6g}"/></inertial>',
                f'    <visual>{mesh}</visual>', f'    <collision>{mesh}</collision>', '  </link>']
    for name, parent, child, xyz, axis, effort, velocity in JOINTS:
        out += [f'  <joint name="{name}" type="revolute">', f'    <parent link="{parent}"/><child link="{child}"/>',
                f'    <origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}"/><axis xyz="{AXES[axis]}"/>',
                f'    <limit lower="-3.1416" upper="3.1416" effort="{effort}" velocity="{velocity}"/>',
                '  </joint>']
    out.append('</robot>')
    with open('ur10e_like.urdf', 'w') as f:
        f.write('\n'.join(out) + '\n')


if __name__ == '__main__':
    main()
