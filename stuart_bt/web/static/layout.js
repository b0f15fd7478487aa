// Where the tree view puts each node: one column per depth, left to right, and a band of rows
// for every subtree.
//
// A subtree's band is as tall as all the rows under it: a node drawn without children (a leaf,
// or a collapsed subtree) takes one row of its own, and a node with children spans from its
// first child's band to its last child's. The node sits at the middle of its first and last
// child, which is inside its own band. Two nodes of one column are in different subtrees, so
// their bands do not share a row, and their centres are at least one ROW apart, more than a box
// is tall: no two boxes of a column overlap, whatever the shape (a chain of decorators, a wide
// sequence, a mix). Boxes of different columns cannot meet, a column being wider than a box.
//
// Every position is computed as a box's centre and turned into its top-left corner once, at the
// end (the old layout mixed the two: a parent's top went to its children's centre, so a
// decorator over a leaf was drawn half a box low, over its next sibling).

export const BOX_W = 210, BOX_H = 38, COL = 250, ROW = 48;

// {boxes: Map path -> {x, y, depth} (top-left corners), edges: [{from, to, x1, y1, x2, y2}]}.
// `nodes`: Map path -> {childPaths}; `isOpen(path)`: whether the node's children are drawn.
export function layoutTree(nodes, root, isOpen) {
  const boxes = new Map();
  const edges = [];
  let nextRow = 0;
  const place = (path, depth) => {
    const node = nodes.get(path);
    let centre;
    if (node.childPaths.length && isOpen(path)) {
      const centres = node.childPaths.map((child) => place(child, depth + 1));
      centre = (centres[0] + centres[centres.length - 1]) / 2;
      node.childPaths.forEach((child, i) => edges.push({ from: path, to: child,
        x1: depth * COL + BOX_W, y1: centre, x2: (depth + 1) * COL, y2: centres[i] }));
    } else {
      centre = nextRow * ROW + BOX_H / 2;
      nextRow += 1;
    }
    boxes.set(path, { x: depth * COL, y: centre - BOX_H / 2, depth });
    return centre;
  };
  if (root !== null && nodes.has(root)) place(root, 0);
  return { boxes, edges };
}
