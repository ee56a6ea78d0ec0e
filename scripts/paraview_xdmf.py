"""DOLFINx XDMF in ParaView (for pvbatch scripts): DOLFINx writes each
function as its own grid on one mesh, which ParaView's XDMF reader returns
as separate pieces. joined() adds a Programmable Filter that puts every
piece's point and cell arrays on the one mesh."""
from paraview.simple import ProgrammableFilter, Xdmf3ReaderS

# Runs inside ParaView's Programmable Filter: one dataset with every piece's
# point and cell arrays (the pieces share points and cells)
JOIN = """
inp = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
if not inp.IsA("vtkCompositeDataSet"):
    out.ShallowCopy(inp)
    return
it = inp.NewIterator()
it.InitTraversal()
first = True
while not it.IsDoneWithTraversal():
    ds = it.GetCurrentDataObject()
    if first:
        out.CopyStructure(ds)
        first = False
    for data, target in ((ds.GetPointData(), out.GetPointData()),
                         (ds.GetCellData(), out.GetCellData())):
        for k in range(data.GetNumberOfArrays()):
            target.AddArray(data.GetArray(k))
    it.GoToNextItem()
"""


def joined(path):
    """(reader, filter) for an XDMF file: the filter's output is one
    unstructured grid with all the functions' arrays; the reader has the
    times (TimestepValues)."""
    reader = Xdmf3ReaderS(FileName=[path])
    reader.UpdatePipelineInformation()
    data = ProgrammableFilter(Input=reader)
    data.OutputDataSetType = "vtkUnstructuredGrid"
    data.Script = JOIN
    return reader, data
