(A hole smaller than the bit: Eagle stepcraft.ulp writes a full circle of zero radius.)
(Mach3 and UCCNC pass over it; LinuxCNC refuses it.)
G21 G90
G00 Z1.000
G00 X13.275Y15.875
G01 Z-0.150 F30
G03 F360
X13.275Y15.875 I0.000
G00 Z1.000
M30
