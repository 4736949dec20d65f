// A small live chart on a canvas: one series, its latest value and its range over the window.

export class Plot {
  constructor(canvas, { label, unit = "", digits = 2, color = "#6cb6ff", points = 240 }) {
    this.canvas = canvas;
    this.label = label;
    this.unit = unit;
    this.digits = digits;
    this.color = color;
    this.points = points;
    this.values = [];
  }

  push(value) {
    if (!Number.isFinite(value)) return;
    this.values.push(value);
    if (this.values.length > this.points) this.values.shift();
    this.draw();
  }

  draw() {
    const c = this.canvas;
    const g = c.getContext("2d");
    const w = (c.width = c.clientWidth * devicePixelRatio);
    const h = (c.height = c.clientHeight * devicePixelRatio);
    g.clearRect(0, 0, w, h);
    g.fillStyle = "rgba(255,255,255,0.05)";
    g.fillRect(0, 0, w, h);
    if (this.values.length === 0) return;
    let lo = Math.min(...this.values);
    let hi = Math.max(...this.values);
    if (hi - lo < 1e-9) {
      hi += Math.abs(hi) * 0.1 + 1e-6;
      lo -= Math.abs(lo) * 0.1 + 1e-6;
    }
    g.strokeStyle = this.color;
    g.lineWidth = devicePixelRatio;
    g.beginPath();
    this.values.forEach((v, i) => {
      const x = (i / (this.points - 1)) * w;
      const y = h - ((v - lo) / (hi - lo)) * (h - 14 * devicePixelRatio) - 2;
      if (i === 0) g.moveTo(x, y);
      else g.lineTo(x, y);
    });
    g.stroke();
    g.fillStyle = "#d0d4da";
    g.font = `${11 * devicePixelRatio}px sans-serif`;
    const last = this.values[this.values.length - 1];
    g.fillText(`${this.label} ${last.toFixed(this.digits)}${this.unit}  ` +
               `[${lo.toFixed(this.digits)}, ${hi.toFixed(this.digits)}]`, 4, 12 * devicePixelRatio);
  }
}
