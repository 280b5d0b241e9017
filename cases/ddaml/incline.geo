<?xml version="1.0" standalone="no"?>
<!DOCTYPE DDA SYSTEM "geometry.dtd">
<!-- ddafit's incline (seed section 2.3) written as the UC Berkeley DDA codes' input:
     a fixed 2:1 slope and a 2.24 x 2.01 m slider on it. Its side and top joints overshoot
     by 0.01 m, as DDA input does; the overshoots are dropped when the blocks are cut. -->
<Berkeley:DDA xmlns:Berkeley="http://www.tsoft.com/~bdoolin/dda">
<Berkeley:Geometry>
   <Berkeley:Edgenodedist distance="0.001"/>
   <Jointlist>
      <Joint type="1"> 0 0 30 -15 </Joint>
      <Joint type="1"> 30 -15 30 -17 </Joint>
      <Joint type="1"> 30 -17 0 -2 </Joint>
      <Joint type="1"> 0 -2 0 0 </Joint>
      <Joint type="1"> 1.99 -1.02 2.91 0.82 </Joint>
      <Joint type="1"> 3.99 -2.02 4.91 -0.18 </Joint>
      <Joint type="1"> 2.88 0.81 4.92 -0.21 </Joint>
   </Jointlist>
   <Fixedpointlist>
      <Point> 10 -6 </Point>
      <Point> 20 -11 </Point>
   </Fixedpointlist>
   <Measuredpointlist>
      <Point> 3.45 -0.6 </Point>
   </Measuredpointlist>
</Berkeley:Geometry>
</Berkeley:DDA>
