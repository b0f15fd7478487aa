"""A YOLO detector for the robot: an ONNX export run through OpenCV's DNN module.

Nothing is downloaded: the weights file must be on disk (``--weights`` / the ``weights`` option);
a missing file is one clear error naming the path. Class names come from a text file (one per
line) next to the weights (``<stem>.names``) or the ``names`` option; YOLOv5/v8 style outputs are
read (boxes as centre, size; v5 adds an objectness column).
"""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from ..core.errors import StuartError
from .detect import DEFAULT_THRESHOLD, Detection, Detector
from .frames import Frame

INPUT_SIZE = 640
NMS_IOU = 0.45


class DetectorConfigError(StuartError, ValueError):
    pass


class YoloDetector(Detector):
    name = "yolo"

    def __init__(self, weights: str | Path | None, names: list[str] | str | Path | None = None,
                 threshold: float = DEFAULT_THRESHOLD, input_size: int = INPUT_SIZE) -> None:
        super().__init__(threshold)
        if not weights:
            raise DetectorConfigError("the yolo detector needs a local ONNX weights file (option 'weights'); "
                                      "nothing is downloaded at run time")
        path = Path(weights)
        if not path.is_file():
            raise DetectorConfigError(f"YOLO weights not found: {path} (give a local .onnx file; nothing is fetched)")
        self.names = _names(names, path)
        try:
            self.net = cv2.dnn.readNetFromONNX(str(path))
        except cv2.error as e:
            why = str(e).strip().splitlines()[-1]
            raise DetectorConfigError(f"cannot load {path} as an ONNX network: {why}") from None
        self.input_size = input_size

    def candidates(self, frame: Frame) -> list[Detection]:
        height, width = frame.rgb.shape[:2]
        blob = cv2.dnn.blobFromImage(frame.rgb, 1 / 255.0, (self.input_size, self.input_size), swapRB=False, crop=False)
        self.net.setInput(blob)
        rows = np.squeeze(self.net.forward())
        if rows.ndim == 2 and rows.shape[0] < rows.shape[1]:  # v8 exports are (4 + classes, N)
            rows = rows.T
        with_objectness = rows.shape[1] == len(self.names) + 5
        scores = rows[:, 5:] * rows[:, 4:5] if with_objectness else rows[:, 4:]
        classes = scores.argmax(axis=1)
        confidences = scores[np.arange(len(rows)), classes]
        sx, sy = width / self.input_size, height / self.input_size
        boxes = [[float((r[0] - r[2] / 2) * sx), float((r[1] - r[3] / 2) * sy), float(r[2] * sx), float(r[3] * sy)]
                 for r in rows]
        keep = cv2.dnn.NMSBoxes(boxes, confidences.astype(float).tolist(), self.threshold * 0.5, NMS_IOU)
        out = []
        for i in np.array(keep).reshape(-1):
            x, y, w, h = boxes[i]
            box = (max(0, int(x)), max(0, int(y)), min(width, int(x + w)), min(height, int(y + h)))
            name = self.names[classes[i]] if classes[i] < len(self.names) else str(int(classes[i]))
            out.append(Detection(name, float(confidences[i]), box))
        return out


def _names(names: list[str] | str | Path | None, weights: Path) -> list[str]:
    if isinstance(names, list):
        return [str(n) for n in names]
    path = Path(names) if names else weights.with_suffix(".names")
    if not path.is_file():
        raise DetectorConfigError(f"YOLO class names not found: {path} (one name per line; option 'names')")
    return [line.strip() for line in path.read_text(encoding="utf-8").splitlines() if line.strip()]
