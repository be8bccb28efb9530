// Single joint (paper §3, Fig. 6; §4.3, Fig. 9): a steel cube below z = 0 and
// a concrete cube above, one hexahedron each, sharing the face z = 0 where
// pushout inserts one joint element. Side a = sqrt(area). Units: mm.
DefineConstant[ a = {1, Name "side of the joint face"} ];

Point(1) = {0, 0, -a}; Point(2) = {a, 0, -a};
Point(3) = {a, a, -a}; Point(4) = {0, a, -a};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1:4} = 2;
Transfinite Surface{1};
Recombine Surface{1};
lower[] = Extrude {0, 0, a} { Surface{1}; Layers{1}; Recombine; };
upper[] = Extrude {0, 0, a} { Surface{lower[0]}; Layers{1}; Recombine; };
Physical Volume("steel", 1) = {lower[1]};
Physical Volume("concrete", 2) = {upper[1]};
