%prog1
(PathScripts.post.uccnc_post with default settings)
(Exported by FreeCAD for UC-CNC)
(Post Processor: PathScripts.post.uccnc_post, version 0.0.4)
(CAM file: )
(Output Time: 2026-11-22 03:20:59.774988)
(Units: 'mm' and 'mm/min')
(preamble: begin)
G17 (Default: XY-plane)
G54 (Default: First coordinate system)
G40 (Default: Cutter radius compensation none)
G49 (Default: Tool Length Offsets: cancel tool length)
G90 (Default: Absolute distance mode selection)
G80 (Cancel canned cycle)
(preamble: done)
(operation initialise: TC: 6mm Endmill)
(operation start: TC: 6mm Endmill)
(TC: 6mm Endmill)
M6 T1
M3 S8000
(operation done: TC: 6mm Endmill)
(operation finalised: TC: 6mm Endmill)
(operation initialise: Facing)
M8 (coolant: flood on)
(operation start: Facing)
(Facing)
G0 Z5.000
G0 X-4.000 Y3.000
G0 Z3.000
G1 Z-0.500 F300.000
G1 X64.000 F1200.000
G1 Y8.000
G1 X-4.000
G1 Y13.000
G1 X64.000
G1 Y18.000
G1 X-4.000
G1 Y23.000
G1 X64.000
G1 Y28.000
G1 X-4.000
G1 Y33.000
G1 X64.000
G1 Y38.000
G1 X-4.000
G0 Z5.000
(operation done: Facing)
M9 (coolant: off)
(operation finalised: Facing)
(operation initialise: Pocket)
M8 (coolant: flood on)
(operation start: Pocket)
(Pocket)
G0 Z5.000
G0 X32.500 Y20.000
G0 Z3.000
G0
G1 Z-0.500 F300.000
G3 X27.500 Z-0.875 I-2.500 J0.000 F1200.000
G3 X32.500 Z-1.250 I2.500
G3 X27.500 Z-1.625 I-2.500
G3 X32.500 Z-2.000 I2.500
G3 X27.500 I-2.500
G3 X32.500 I2.500
G0 X30.000
G0 Z-0.500
G1 Y19.000 Z-2.000
G1 X33.000
G3 X34.000 Y20.000 I0.000 J1.000
G1
G3 X33.000 Y21.000 I-1.000 J0.000
G1 X27.000
G3 X26.000 Y20.000 I0.000 J-1.000
G1
G3 X27.000 Y19.000 I1.000 J0.000
G1 X30.000
G1 Y16.000
G1 X36.000
G3 X37.000 Y17.000 I0.000 J1.000
G1 Y23.000
G3 X36.000 Y24.000 I-1.000 J0.000
G1 X24.000
G3 X23.000 Y23.000 I0.000 J-1.000
G1 Y17.000
G3 X24.000 Y16.000 I1.000 J0.000
G1 X30.000
G0 Z3.000
G0 X32.500 Y20.000
G0
G1 Z-2.000 F300.000
G3 X27.500 Z-2.375 I-2.500 F1200.000
G3 X32.500 Z-2.750 I2.500
G3 X27.500 Z-3.125 I-2.500
G3 X32.500 Z-3.500 I2.500
G3 X27.500 I-2.500
G3 X32.500 I2.500
G0 X30.000
G0 Z-2.000
G1 Y19.000 Z-3.500
G1 X33.000
G3 X34.000 Y20.000 I0.000 J1.000
G1
G3 X33.000 Y21.000 I-1.000 J0.000
G1 X27.000
G3 X26.000 Y20.000 I0.000 J-1.000
G1
G3 X27.000 Y19.000 I1.000 J0.000
G1 X30.000
G1 Y16.000
G1 X36.000
G3 X37.000 Y17.000 I0.000 J1.000
G1 Y23.000
G3 X36.000 Y24.000 I-1.000 J0.000
G1 X24.000
G3 X23.000 Y23.000 I0.000 J-1.000
G1 Y17.000
G3 X24.000 Y16.000 I1.000 J0.000
G1 X30.000
G0 Z3.000
G0 X32.500 Y20.000
G0 Z5.000
(operation done: Pocket)
M9 (coolant: off)
(operation finalised: Pocket)
(operation initialise: Profile)
M8 (coolant: flood on)
(operation start: Profile)
(Profile)
G0 Z5.000
G0 X30.000 Y2.000
G0 Z3.000
G1 Z-2.000 F300.000
G1 X50.000 F1200.000
G3 X58.000 Y10.000 I0.000 J8.000
G1 Y30.000
G3 X50.000 Y38.000 I-8.000 J0.000
G1 X10.000
G3 X2.000 Y30.000 I0.000 J-8.000
G1 Y10.000
G3 X10.000 Y2.000 I8.000 J0.000
G1 X30.000
G0 Z5.000
(operation done: Profile)
M9 (coolant: off)
(operation finalised: Profile)
(operation initialise: TC: 5mm Drill)
(operation start: TC: 5mm Drill)
(TC: 5mm Drill)
M6 T2
M3 S3000
(operation done: TC: 5mm Drill)
(operation finalised: TC: 5mm Drill)
(operation initialise: Drilling)
(operation start: Drilling)
(Drilling)
G0 Z5.000
(Begin Drilling)
G0
G90
G99
G0 X8.000 Y8.000
G0 Z3.000
G81 Z-6.000 R1.000 F150.000
G0 X52.000
G0 Z3.000
G81 Z-6.000
G0 Y32.000
G0 Z3.000
G81 Z-6.000
G0 X8.000
G0 Z3.000
G81 Z-6.000
G80
G0 Z5.000
(operation done: Drilling)
(operation finalised: Drilling)
(operation initialise: PeckDrilling)
(operation start: PeckDrilling)
(PeckDrilling)
G0 Z5.000
(Begin Drilling)
G0
G90
G98
G0 X20.000 Y20.000
G0 Z3.000
G83 Z-6.000 R1.000 F150.000 Q2.000
G0 X40.000
G0 Z3.000
G83 Z-6.000
G80
G0 Z5.000
(operation done: PeckDrilling)
(operation finalised: PeckDrilling)
(postamble: begin)
M05 (stop spindle)
G17 (Default: XY-plane)
G54 (Default: First coordinate system)
G40 (Default: Cutter radius compensation none)
G90 (Default: Absolute distance mode selection)
G80 (Cancel canned cycle)
M30 (Stop program and rewind code)
(postamble: done)
