"""pvpython: the number of cells ParaView's Threshold keeps from a bed's .xmf for radius in
[LO, HI] (m), printed alone: filters see the particles only when the XDMF gives them cells."""
import sys

from paraview import simple as pv

xmf, lo, hi = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
for reader in (pv.XDMFReader(FileNames=[xmf]), pv.Xdmf3ReaderS(FileName=[xmf])):
    kept = pv.Threshold(Input=reader, Scalars=["POINTS", "radius"], LowerThreshold=lo,
                        UpperThreshold=hi)
    kept.UpdatePipeline()
    print(kept.GetDataInformation().GetNumberOfCells())
