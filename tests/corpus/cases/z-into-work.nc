(Estlcam's post with "Scale z=-1": +Z points into the work on this machine.)
(Rapids cross at Z-25, the cuts run at Z0.5 and deeper: read as Z up, every plunge is a collision.)
(Required tools:)
(HSS 1-Flute Endmill, 3.175mm)
G90
M03 S9000
G00 Z-25.0000
G00 X0.0000 Y0.0000
G00 Z-0.5000
G01 Z0.5000 F300
G01 X20.0000 F600
G01 Z1.0000 F300
G01 X0.0000 F600
G00 Z-25.0000
G00 X0.0000 Y10.0000
G00 Z-0.5000
G01 Z0.5000 F300
G01 X20.0000 F600
G00 Z-25.0000
M05
M30
