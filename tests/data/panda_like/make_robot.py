#!/usr/bin/env python3
"""Writes panda_like.urdf and its meshes (ASCII STL prisms, 16 sides): a
Franka Panda-sized 7-joint arm. Kinematics (the joint origins of
franka_description's panda_arm, i.e. Franka's modified DH), joint ranges,
velocity and effort limits are Franka's published ones; masses, centres of
mass and inertias are approximately those identified by Gaz et al. (2019,
"Dynamic identification of the Franka Emika Panda robot"); the collision
shapes are prisms around the links, coarser than Franka's meshes. Not a
vendor file: a fixture of the same size and limits. Deterministic; run from
this folder."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
from prism_stl import prism_triangles, write_stl  # noqa: E402

PI = math.pi


# link: (prisms (axis, start, end, radius, offset), mass [kg], centre of mass [m],
#        inertia about it (ixx, ixy, ixz, iyy, iyz, izz) [kg m²])
LINKS = {
    'panda_link0': ([('z', 0.0, 0.14, 0.09, (0, 0, 0))], 3.06, (-0.025, 0, 0.06),
                    (0.0090, 0, 0, 0.0115, 0, 0.0120)),
    'panda_link1': ([('z', -0.19, 0.0, 0.06, (0, 0, 0))], 4.970684, (0.003875, 0.002081, -0.04762),
                    (0.70337, -0.000139, 0.006772, 0.70661, 0.019169, 0.009117)),
    'panda_link2': ([('y', -0.20, 0.0, 0.06, (0, 0, 0))], 0.646926, (-0.003141, -0.02872, 0.003495),
                    (0.007962, -0.003925, 0.010254, 0.02811, 0.000704, 0.025995)),
    'panda_link3': ([('z', -0.11, 0.03, 0.06, (0, 0, 0)), ('x', 0.0, 0.0825, 0.05, (0, 0, 0))],
                    3.228604, (0.027518, 0.039252, -0.066502),
                    (0.037242, -0.004761, -0.011396, 0.036155, -0.012805, 0.01083)),
    'panda_link4': ([('x', -0.0825, 0.0, 0.055, (0, 0, 0)), ('y', 0.0, 0.25, 0.05, (-0.0825, 0, 0))],
                    3.587895, (-0.05317, 0.104419, 0.027454),
                    (0.025853, 0.007796, -0.001332, 0.019552, 0.008641, 0.028323)),
    'panda_link5': ([('z', -0.13, 0.0, 0.05, (0, 0, 0))], 1.225946, (-0.011953, 0.041065, -0.038437),
                    (0.035549, -0.002117, -0.004037, 0.029474, 0.000229, 0.008627)),
    'panda_link6': ([('x', 0.0, 0.088, 0.045, (0, 0, 0))], 1.666555, (0.060149, -0.014117, -0.010517),
                    (0.001964, 0.000109, -0.001158, 0.004354, 0.000341, 0.005433)),
    'panda_link7': ([('z', -0.02, 0.107, 0.045, (0, 0, 0))], 0.735522, (0.010517, -0.004252, 0.061597),
                    (0.012516, -0.000428, -0.001196, 0.010027, -0.000741, 0.004815)),
}
# joint: (parent, child, origin xyz, origin roll, lower, upper [rad], effort [N m], velocity [rad/s])
JOINTS = [
    ('panda_joint1', 'panda_link0', 'panda_link1', (0, 0, 0.333), 0.0, -2.8973, 2.8973, 87, 2.1750),
    ('panda_joint2', 'panda_link1', 'panda_link2', (0, 0, 0), -PI / 2, -1.7628, 1.7628, 87, 2.1750),
    ('panda_joint3', 'panda_link2', 'panda_link3', (0, -0.316, 0), PI / 2, -2.8973, 2.8973, 87, 2.1750),
    ('panda_joint4', 'panda_link3', 'panda_link4', (0.0825, 0, 0), PI / 2, -3.0718, -0.0698, 87, 2.1750),
    ('panda_joint5', 'panda_link4', 'panda_link5', (-0.0825, 0.384, 0), -PI / 2, -2.8973, 2.8973, 12, 2.6100),
    ('panda_joint6', 'panda_link5', 'panda_link6', (0, 0, 0), PI / 2, -0.0175, 3.7525, 12, 2.6100),
    ('panda_joint7', 'panda_link6', 'panda_link7', (0.088, 0, 0), PI / 2, -2.8973, 2.8973, 12, 2.6100),
]


def main():
    out = ['<?xml version="1.0"?>', '<robot name="panda_like">']
    for name, (prisms, mass, com, (ixx, ixy, ixz, iyy, iyz, izz)) in LINKS.items():
        tris = []
        for p in prisms:
            tris += prism_triangles(*p)
        write_stl(f'meshes/{name}.stl', name, tris)
        mesh = f'<geometry><mesh filename="meshes/{name}.stl"/></geometry>'
        out += [f'  <link name="{name}">',
                f'    <inertial><origin xyz="{com[0]} {com[1]} {com[2]}"/><mass value="{mass}"/>'
                f'<inertia ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" iyy="{iyy}" iyz="{iyz}" izz="{izz}"/></inertial>',
                f'    <visual>{mesh}</visual>', f'    <collision>{mesh}</collision>', '  </link>']
    for name, parent, child, xyz, roll, lower, upper, effort, velocity in JOINTS:
        out += [f'  <joint name="{name}" type="revolute">', f'    <parent link="{parent}"/><child link="{child}"/>',
                f'    <origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}" rpy="{roll!r} 0 0"/><axis xyz="0 0 1"/>',
                f'    <limit lower="{lower}" upper="{upper}" effort="{effort}" velocity="{velocity}"/>',
                '  </joint>']
    out.append('</robot>')
    with open('panda_like.urdf', 'w') as f:
        f.write('\n'.join(out) + '\n')


if __name__ == '__main__':
    main()
