// Unit box with tagged faces, volume, one corner point and one edge (to produce point and line elements).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Mesh.CharacteristicLengthMax = 0.3;
Physical Point(101) = {1};
Physical Curve(201) = {1};
Physical Surface(1) = {1, 2};
Physical Surface(2) = {3, 4};
Physical Surface(3) = {5, 6};
Physical Volume(10) = {1};
